// The plugin module: only the manifest. Everything else is in the core library.
#include "rollsense/nearest_centroid/nearest_centroid.hpp"
#include "rollsense/plugin.hpp"

ROLLSENSE_PLUGIN(rollsense::nearest_centroid::NearestCentroid, classifier, "nearest_centroid", "1.0.0",
                 "Nearest (shrunken) centroid on standardised features; scores = softmax of -distance",
                 rollsense::nearest_centroid::nearest_centroid_schema)
