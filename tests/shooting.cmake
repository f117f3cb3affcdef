# Shooting, the fixed-point search and branches of periodic orbits (issue 4).
sc_add_test(test_shooting)
sc_add_test(test_fixed_points)
sc_add_test(test_branch)
