#include "test_util.h"
int main(void) { return tu_finish(); }
