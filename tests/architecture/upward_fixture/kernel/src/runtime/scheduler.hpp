// Fixture for the layer check: a kernel header that includes the analysis layer.
#pragma once
#include "analysis/pipeline.hpp"
