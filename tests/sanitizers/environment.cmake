# The sanitizers' runtime options in a -DBLADESTAB_SANITIZE build (tests/CMakeLists.txt): every test
# runs with them, and so does every bladestab a test starts (it inherits the environment). A report
# ends the process with a non-zero status (the build has -fno-sanitize-recover=all), so it fails the
# test, also when it comes from a bladestab whose one-line stderr a test checks.
# OpenBLAS runs single-threaded there, as the program runs it: its own threads are not
# instrumented, and their synchronisation unseen by ThreadSanitizer would be reported as races on
# the buffers they share with the caller; the threads under test are the library's.
set(dir ${CMAKE_CURRENT_LIST_DIR})
set(BLADESTAB_SANITIZER_ENVIRONMENT
    "OPENBLAS_NUM_THREADS=1"
    "ASAN_OPTIONS=detect_leaks=1:strict_init_order=1:check_initialization_order=1:detect_stack_use_after_return=1"
    "LSAN_OPTIONS=suppressions=${dir}/lsan.supp:print_suppressions=0"
    "UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1"
    "TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1:suppressions=${dir}/tsan.supp:print_suppressions=0")
