list(APPEND SC_SOURCES
  continuation/linsolve.c
  continuation/linsolve_dense.c
  continuation/linsolve_klu.c
  continuation/product_eigs.c
  continuation/branch.c
  continuation/map1d.c
  continuation/curve.c
  continuation/curve_ms.c
  continuation/normal_form.c
  continuation/mapn_system.c
  continuation/nf_tests.c)
