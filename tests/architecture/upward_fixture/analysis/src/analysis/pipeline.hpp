// Fixture for the layer check: a header of the analysis layer.
#pragma once
