// What a classifier returns, checked before anything uses it, and what it
// throws caught. A plugin is written outside this repository; its prediction
// indexes the confusion matrix (label) and fills evaluation.json, `rollsense
// predict` and live identification (scores, class name), so a label outside
// its classes or named as another, scores that are not a distribution over the
// classes (one per class, finite, >= 0, summing to 1) or whose highest is not
// the label's, and an exception from any call, are a plugin error naming the
// plugin, never a wrong figure, a null in a file or an "unexpected error".
#pragma once

#include <string>

#include "analysis/learn/cross_validation.hpp"

namespace rollsense::learn {

// The classes predictions are expected of: a label in [0, class_names.size())
// named class_names[label], one finite score >= 0 per class, the scores summing
// to 1 and the label's the highest (both within 1e-6, for rounding); `who`
// names the classifier in the error.
Status check_prediction(const Prediction& p, const std::vector<std::string>& class_names, const std::string& who);

// Every dimension of `space` names a parameter of `schema`, is one tuning can
// search (a finite, non-empty range or choices; a log scale above 0; a real
// scale only for a number) and stays within what the schema accepts (both ends,
// every choice): tuning sets them as parameters, so any of these would fail
// only after the preset's cross-validation, when tuning first configures a
// classifier (reviews); a plugin error naming `who`, the parameter and the way out.
Status check_search_space(const SearchSpace& space, const ParamSchema& schema, const std::string& who);

// `status` in the context of the classifier `name` (a --classifier entry), unless its message starts with the
// plugin of that name already (user review: "classifier 'knn': classifier plugin 'knn': ...").
Status in_classifier(Status status, const std::string& name);

// `inner` behind check_prediction on every predict (classes: its class_names()
// once trained or loaded, where none is a plugin error) and check_search_space
// against `schema`, its parameters, on every search_space; an exception from
// train, load, predict, save or invoke is returned as a plugin error naming `who` with the exception's text,
// and load's errors name `who`; one from input, search_space or class_names,
// which have no error return, is thrown on as that error (a StatusError).
ClassifierPtr checked_classifier(ClassifierPtr inner, std::string who, ParamSchema schema);

}  // namespace rollsense::learn
