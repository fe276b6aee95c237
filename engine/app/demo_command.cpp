// vct demo: placeholder until the window lands (being written).
#include "app/commands.h"
#include "core/error.h"

namespace vct {
int runDemoCommand(int, char**, int) { throw Error("demo: not built yet"); }
}  // namespace vct
