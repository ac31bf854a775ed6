// The plugin module: only the manifest. Everything else is in the core library.
#include "rollsense/bagged_trees/bagged_trees.hpp"
#include "rollsense/plugin.hpp"

ROLLSENSE_PLUGIN(rollsense::bagged_trees::BaggedTrees, classifier, "bagged_trees", "1.0.0",
                 "Bagged classification trees (MATLAB Classification Learner 'Bagged Trees'): bootstrap, Gini, "
                 "posterior averaging",
                 rollsense::bagged_trees::bagged_trees_schema)
