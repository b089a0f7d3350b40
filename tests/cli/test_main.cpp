// test_main.cpp — the doctest runner for the command-line tests of `contactlab`.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
