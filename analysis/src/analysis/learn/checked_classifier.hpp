// What a classifier returns, checked before anything uses it. A plugin is
// written outside this repository; its prediction indexes the confusion matrix
// (label) and fills evaluation.json, `rollsense predict` and live
// identification (scores, class name), so a label outside its classes or named
// as another, a score count other than its class count or a score that is not
// a finite number is a plugin error naming the plugin, never a wrong figure or
// a null in a file.
#pragma once

#include <string>

#include "analysis/learn/cross_validation.hpp"

namespace rollsense::learn {

// The classes predictions are expected of: a label in [0, class_names.size())
// named class_names[label], one finite score per class; `who` names the
// classifier in the error.
Status check_prediction(const Prediction& p, const std::vector<std::string>& class_names, const std::string& who);

// `inner` behind check_prediction on every predict (classes: its class_names()
// once trained or loaded). Everything else is passed through.
ClassifierPtr checked_classifier(ClassifierPtr inner, std::string who);

}  // namespace rollsense::learn
