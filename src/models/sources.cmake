list(APPEND SC_SOURCES src/models/smooth_maps.c src/models/bk2.c
  src/models/bk2_event.c
  src/models/bk2_map.c src/models/bk2_numerical.c
  src/models/bk2_jet.c
  src/models/bk2_quad.c
  src/models/maps2d.c
  src/models/chain.c src/models/chain_phase.c src/models/chain_vw.c
  src/models/chain_border.c
  src/models/chain_thresholds.c src/models/chain_events.c
  src/models/chain_jet.c
  src/models/bcnf.c)
