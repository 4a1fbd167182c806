// Compiled against the engine layer's include root by the layering test: the engine must not
// see the storage layer, so this include must fail to resolve.
#include "storage/flow_state.hpp"
