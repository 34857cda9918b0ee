// The AddressSanitizer settings every fuzz target of the project starts with (ASAN_OPTIONS, and
// the [asan] section of a target's .options file under ClusterFuzzLite, still override them).
//
// malloc_context_size=2: ASan records the call stack of every allocation in a store that never
// shrinks. GMP's allocations come from code built without frame pointers, so beyond the second
// frame those stacks are garbage that differs from call to call: measured on fuzz_consumers, the
// store grew to 7.9 million distinct stacks (377 MB after 51k runs, 37-42% of the time spent
// adding to it) and the rate halved within 5 minutes. With two frames it stays at about 2,000.
// A heap error's report still names the allocating function and its caller.
extern "C" const char* __asan_default_options() {
  return "malloc_context_size=2";
}
