# Accuracy (issue 11): the quad-precision reference path, the presets'
# promises held against it, and the extremes of the parameter ranges.
sc_add_test(test_quad)
