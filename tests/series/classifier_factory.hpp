// A classifier core (linked in, no plugin loading) as the learning pipeline's
// factory: parameters validated against its schema, then configured.
#pragma once

#include <memory>

#include "analysis/learn/cross_validation.hpp"
#include "rollsense/params.hpp"

namespace rollsense::testing {

template <typename T>
learn::ClassifierFactory factory_of(ParamSchema schema) {
    return [schema](const ParamSet& raw) -> Result<learn::ClassifierPtr> {
        auto params = validate_params(schema, raw.values(), "test");
        if (!params) return params.error();
        auto c = std::make_shared<T>();
        if (auto s = c->on_configure(*params, {}); !s) return s;
        return learn::ClassifierPtr(c);
    };
}

}  // namespace rollsense::testing
