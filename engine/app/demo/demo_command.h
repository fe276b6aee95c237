// vct demo: the subcommand that opens a window and shows the frame live. Returns the process exit code;
// errors are thrown (vct::UsageError → 2, vct::Error → 1) and printed as one line by main().
#pragma once

namespace vct {

int runDemoCommand(int argc, char** argv, int first);

}  // namespace vct
