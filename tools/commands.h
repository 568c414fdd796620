// Every vorogeo subcommand: int run(args after the subcommand name) -> exit status.
#pragma once

namespace vorogeo::tools {

struct Command {
    const char* name;
    const char* summary;
    int (*run)(int argc, char** argv);
};

// The table lives in main.cpp; each command is implemented in cmd_<name>.cpp.
const Command* commands();
int commandCount();

}  // namespace vorogeo::tools
