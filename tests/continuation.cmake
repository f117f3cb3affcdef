# Tests of the generic continuation layer (continuation/).
sc_add_test(test_linalg)
sc_add_test(test_continuation)
sc_add_test(test_curve)
