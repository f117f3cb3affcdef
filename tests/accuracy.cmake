# Accuracy (issue 11): the quad-precision reference path, the presets'
# promises held against it, and the extremes of the parameter ranges.
sc_add_test(test_quad)
sc_add_test(test_extremes)
set_tests_properties(test_extremes PROPERTIES TIMEOUT 300)
