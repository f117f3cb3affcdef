sc_add_test(test_common)
sc_add_test(test_guard)
sc_add_test(test_bk2)
