list(APPEND SC_SOURCES src/map/map.c)
list(APPEND SC_SOURCES src/map/shooting.c)
list(APPEND SC_SOURCES src/map/mapn.c src/map/map_events.c)
list(APPEND SC_SOURCES src/map/shooting_n.c)
