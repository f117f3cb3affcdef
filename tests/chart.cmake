# Period detection and two-parameter charts (issue 3).
sc_add_test(test_period)
sc_add_test(test_chart)
