// Preloaded (LD_PRELOAD) into every process of the AddressSanitizer run: dlclose does nothing,
// so libraries stay mapped until exit. The Vulkan loader unloads its layers and drivers in
// vkDestroyInstance; LeakSanitizer reports at exit, and a leak whose allocating library is
// gone cannot be named, so its suppression (lsan.supp) would not match. Built without
// sanitizers: it is also preloaded into the shells, perl and xargs that the tests run.
extern "C" int dlclose(void*) { return 0; }
