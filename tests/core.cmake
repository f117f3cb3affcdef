sc_add_test(test_common)
