set(SC_CLI_SOURCES src/cli/main.c)
