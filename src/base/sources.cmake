# sources of src/base: status codes, messages, the accuracy object,
# convergence tests and number parsing, shared by every layer.
list(APPEND SC_SOURCES src/base/common.c)
