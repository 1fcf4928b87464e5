// LeakSanitizer reads this hook at start-up (sanitizer builds only; otherwise nothing calls it). Mesa's
// OSMesa keeps per-thread context state it never frees; that is not ours to fix, everything else is checked.
extern "C" const char* __lsan_default_suppressions() { return "leak:libOSMesa.so\n"; }
