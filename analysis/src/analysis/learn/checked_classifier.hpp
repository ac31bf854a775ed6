// What a classifier returns, checked before anything uses it. A plugin is
// written outside this repository; its prediction indexes the confusion matrix
// (label) and fills evaluation.json, `rollsense predict` and live
// identification (scores), so a label outside its classes, a score count other
// than its class count or a score that is not a finite number is a plugin error
// naming the plugin, never a wrong figure or a null in a file.
#pragma once

#include <string>

#include "analysis/learn/cross_validation.hpp"

namespace rollsense::learn {

// `classes` predictions are expected of (label in [0, classes), one finite
// score per class); `who` names the classifier in the error.
Status check_prediction(const Prediction& p, std::size_t classes, const std::string& who);

// `inner` behind check_prediction on every predict (classes: its class_names()
// once trained or loaded). Everything else is passed through.
ClassifierPtr checked_classifier(ClassifierPtr inner, std::string who);

}  // namespace rollsense::learn
