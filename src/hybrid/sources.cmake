list(APPEND SC_SOURCES src/hybrid/guard.c)
