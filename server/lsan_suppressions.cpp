// LeakSanitizer reads these hooks at start-up (sanitizer builds only; otherwise nothing calls them). Mesa's
// OSMesa keeps per-thread context state it never frees; that is not ours to fix, everything else is checked.
// The list of suppressions used is not printed: the CLI's stderr is its JSON error, which callers parse.
extern "C" const char* __lsan_default_suppressions() { return "leak:libOSMesa.so\n"; }
extern "C" const char* __lsan_default_options() { return "print_suppressions=0"; }
