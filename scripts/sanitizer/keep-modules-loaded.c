/*
 * Preloaded (LD_PRELOAD) into the sanitizer test run by scripts/sanitize.sh: dlclose does
 * nothing, so shared libraries loaded at run time stay mapped until the process exits.
 *
 * Why: Mesa loads its driver (swrast_dri.so, llvmpipe) with dlopen and unloads it when the
 * X display closes. LeakSanitizer, which checks at exit, then sees the blocks the driver still
 * points to from its globals as leaks "from <unknown module>" (the frames of an unloaded
 * library cannot be named), so no suppression file entry can match them. Measured with a plain
 * vtkRenderWindow render under xvfb-run: 3 such reports (240 bytes) without this file, none
 * with it. Nothing in the project or its tests relies on unloading a library.
 */
int dlclose(void* handle)
{
  (void)handle;
  return 0;
}
