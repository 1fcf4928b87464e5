// LeakSanitizer's built-in suppression hook, read when the test binary starts (so plain runs and ctest alike).
// libOSMesa never frees the framebuffer records OSMesaMakeCurrent allocates (one per context; the
// contexts here live for the process, as in the service) nor a few screen globals: Mesa's leaks, bounded, not ours.
extern "C" const char* __lsan_default_suppressions() { return "leak:libOSMesa.so\n"; }
