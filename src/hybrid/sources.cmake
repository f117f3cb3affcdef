list(APPEND SC_SOURCES src/hybrid/guard.c src/hybrid/guard_long.c)
