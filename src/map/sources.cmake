list(APPEND SC_SOURCES src/map/map.c)
