list(APPEND SC_SOURCES continuation/common.c)
