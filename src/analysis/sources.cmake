# sources of src/analysis
list(APPEND SC_SOURCES src/analysis/period.c src/analysis/periodn.c
  src/analysis/chart.c)
list(APPEND SC_SOURCES src/analysis/sweep.c)
list(APPEND SC_SOURCES src/analysis/fixed_points.c)
list(APPEND SC_SOURCES src/analysis/branch_orbit.c
  src/analysis/branch_segment.c
  src/analysis/branch_border.c
  src/analysis/branch_switch.c
  src/analysis/branch_marks.c
  src/analysis/branch_ms.c
  src/analysis/branchn.c
  src/analysis/branchn_special.c
  src/analysis/branchn_border.c)
list(APPEND SC_SOURCES src/analysis/curve.c
  src/analysis/curve_border.c
  src/analysis/curven.c
  src/analysis/border_list.c)
list(APPEND SC_SOURCES src/analysis/fixed_points_n.c)
