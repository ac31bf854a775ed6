// The plugin module: only the manifest. Everything else is in the core library.
#include "rollsense/minirocket/minirocket.hpp"
#include "rollsense/plugin.hpp"

ROLLSENSE_PLUGIN(rollsense::minirocket::MiniRocket, classifier, "minirocket", "1.0.0",
                 "MiniRocket (Dempster et al., KDD 2021) on prepared multichannel series: 84 fixed kernels, PPV "
                 "pooling, ridge with leave-one-out α",
                 rollsense::minirocket::minirocket_schema)
