/* Preloaded by scripts/sanitize.sh into every test process (LD_PRELOAD).
 *
 * Mesa's EGL unloads its driver (swrast_dri.so with llvmpipe and LLVM) in
 * eglTerminate. Memory the driver still points to from its own globals then
 * looks leaked to LeakSanitizer, with stacks ending in "<unknown module>" that
 * no suppression can name. Keeping every library loaded leaves those blocks
 * reachable, so LeakSanitizer reports only what is really lost. Built without
 * sanitizers, so it can also sit in the (unsanitized) python3 of BenchPlumbing. */
int dlclose(void *handle) {
  (void)handle;
  return 0;
}
