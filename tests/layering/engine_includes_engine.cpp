// The control for the layering test: an include within the engine layer resolves.
#include "engine/check.hpp"
