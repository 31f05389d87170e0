/* A minimal non-Python FMI 2.0 co-simulation host, for benchmarks/fmu_exit_check.py --c-host.
 *
 *     fmi_c_host LIBRARY GUID RESOURCE_URI [SCENE [SCENE_FILE_VALUE_REFERENCE]]
 *
 * Like libcosim or any C/C++ importer: loads the FMU's native library (which then starts
 * Python itself: PythonFMU's PyState), instantiates it, sets the parameter scene_file
 * (default "creep_only_table"; its value reference, default 0, from modelDescription.xml),
 * initialises, makes 10 steps of 1 ms, terminates, frees the instance
 * and returns from main, so that exit() runs the atexit handlers, the C++ static destructors
 * and the libraries' destructors: the path on which PythonFMU finalises the interpreter.
 * Prints "done <status>" before returning; the exit status is the OR of the FMI statuses.
 * The host has to provide libpython (LD_PRELOAD), which fmu_exit_check.py does. */
#include <dlfcn.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

typedef void *Component;
typedef struct {
    void (*logger)(void *, const char *, int, const char *, const char *, ...);
    void *(*allocate_memory)(size_t, size_t);
    void (*free_memory)(void *);
    void *step_finished;
    void *component_environment;
} Callbacks;

static void logger(void *env, const char *name, int status, const char *category,
                   const char *message, ...)
{
    (void)env; (void)name; (void)category;
    if (status > 1) fprintf(stderr, "[status %d] %s\n", status, message);
}

static void *symbol(void *library, const char *name)
{
    void *f = dlsym(library, name);
    if (!f) { fprintf(stderr, "missing %s\n", name); exit(4); }
    return f;
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: %s LIBRARY GUID RESOURCE_URI [SCENE [VR]]\n", argv[0]);
        return 2;
    }
    void *library = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!library) { fprintf(stderr, "%s\n", dlerror()); return 2; }
    Callbacks callbacks = {logger, calloc, free, NULL, NULL};
    Component (*instantiate)(const char *, int, const char *, const char *, const Callbacks *,
                             int, int) = symbol(library, "fmi2Instantiate");
    int (*setup)(Component, int, double, int, double) = symbol(library, "fmi2SetupExperiment");
    int (*enter)(Component) = symbol(library, "fmi2EnterInitializationMode");
    int (*set_string)(Component, const unsigned *, size_t, const char *const *) =
        symbol(library, "fmi2SetString");
    int (*leave)(Component) = symbol(library, "fmi2ExitInitializationMode");
    int (*step)(Component, double, double, int) = symbol(library, "fmi2DoStep");
    int (*terminate)(Component) = symbol(library, "fmi2Terminate");
    void (*free_instance)(Component) = symbol(library, "fmi2FreeInstance");

    Component c = instantiate("wrc", 1 /* fmi2CoSimulation */, argv[2], argv[3], &callbacks, 0, 0);
    if (!c) { fprintf(stderr, "fmi2Instantiate failed\n"); return 3; }
    const unsigned scene_file = argc > 5 ? (unsigned)strtoul(argv[5], NULL, 10) : 0;
    const char *scene = argc > 4 ? argv[4] : "creep_only_table";
    int status = setup(c, 0, 0.0, 0, 0.0);
    status |= enter(c);
    status |= set_string(c, &scene_file, 1, &scene);
    status |= leave(c);
    for (int k = 0; k < 10; k++) status |= step(c, k * 1e-3, 1e-3, 1);
    status |= terminate(c);
    free_instance(c);
    printf("done %d\n", status);
    fflush(stdout);
    return status;
}
