/* Bad input, never misread: the standing gate of the `gomboc` command and its scene reader.
 *
 * Every row of the table is one bad input, a scene file or command-line options, given to the real
 * binary ($GOMBOC_BIN) in a fresh directory that already holds a file of its own. A row passes when
 * the exit status is the one stated (2 for bad input, 1 for a computation or a write that failed), the
 * message names the file and line or the option, the key, and the allowed range, and the directory
 * is byte for byte what it was: no file appeared, none changed, none vanished. Rows a fuzzer found
 * are added here too. Beside the table: values that are strict but valid are accepted, paths of any
 * length work, temporaries are removed after SIGTERM and after a kill -9, and the ranges written in
 * cases/README.md are the ranges the reader enforces. */
#include "gb_atlas.h"
#include "gb_case.h"
#include "gb_check.h"
#include "verify_sections.h"
#include "bad_input.h"

#include <dirent.h>
#include <errno.h>
#include <ftw.h>
#include <math.h>
#include <sys/file.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

/* The binary as an absolute path: every row runs in its own directory. */
const char *bad_input_binary(void)
{
    static char path[4096];
    if (!path[0] && !realpath(getenv("GOMBOC_BIN") ? getenv("GOMBOC_BIN") : "build/gomboc", path))
        snprintf(path, sizeof path, "%s", getenv("GOMBOC_BIN") ? getenv("GOMBOC_BIN") : "build/gomboc");
    return path;
}

/* A started command's signals as a check needs them, whatever this harness inherited (nohup, a background
 * job): SIGHUP, SIGINT, SIGQUIT and SIGTERM at their defaults and none blocked; then `ignored` (0: none) ignored,
 * as a parent that ignores it leaves it. */
void bad_input_child_signals(int ignored)
{
    static const int reset[] = {SIGHUP, SIGINT, SIGQUIT, SIGTERM};
    for (size_t k = 0; k < sizeof reset / sizeof reset[0]; k++) signal(reset[k], SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, NULL);
    if (ignored) signal(ignored, SIG_IGN);
}

/* ---- a directory's state: every entry's name, type, size, link target and content hash ---------- */

static unsigned long long fnv1a(const unsigned char *p, size_t n, unsigned long long h)
{
    for (size_t k = 0; k < n; k++) h = (h ^ p[k]) * 1099511628211ull;
    return h;
}

/* A text that changes when anything in `dir` (not below it) changes. malloc'd. */
char *bad_input_snapshot(const char *dir)
{
    size_t cap = 4096, used = 0;
    char *out = calloc(cap, 1);
    struct dirent **names = NULL;
    const int n = scandir(dir, &names, NULL, alphasort);
    for (int k = 0; k < n; k++) {
        char path[4096], line[1024];
        snprintf(path, sizeof path, "%s/%s", dir, names[k]->d_name);
        struct stat st;
        unsigned long long h = 1469598103934665603ull;
        if (lstat(path, &st) == 0 && S_ISREG(st.st_mode)) {
            FILE *f = fopen(path, "rb");
            unsigned char buf[8192];
            size_t got;
            while (f && (got = fread(buf, 1, sizeof buf, f)) > 0) h = fnv1a(buf, got, h);
            if (f) fclose(f);
        } else if (S_ISLNK(st.st_mode)) {
            char target[1024] = "";
            const ssize_t len = readlink(path, target, sizeof target - 1);
            h = fnv1a((const unsigned char *)target, len > 0 ? (size_t)len : 0, h);
        }
        const int len = snprintf(line, sizeof line, "%s %o %lld %016llx\n", names[k]->d_name, (unsigned)st.st_mode,
                                 (long long)st.st_size, h);
        if (used + (size_t)len + 1 > cap) out = realloc(out, cap = 2 * cap + (size_t)len);
        memcpy(out + used, line, (size_t)len + 1);
        used += (size_t)len;
        free(names[k]);
    }
    free(names);
    return out;
}

/* Run `command` (a shell fragment) in `dir`, its standard error and output captured in `out`. */
int bad_input_run_in(const char *dir, const char *command, char *out, size_t cap)
{
    size_t size = strlen(dir) + strlen(command) + 64;
    char *shell = malloc(size);
    /* A command that hangs (a FIFO opened for reading) is ended after 60 s: exit 124 fails its row. */
    snprintf(shell, size, "cd '%s' && { timeout 60 %s ; } 2>&1; echo \"@@exit=$?\"", dir, command);
    FILE *p = popen(shell, "r");
    free(shell);
    size_t used = 0;
    out[0] = '\0';
    if (!p) return -1;
    while (used + 1 < cap && fgets(out + used, (int)(cap - used), p)) used += strlen(out + used);
    while (fgetc(p) != EOF) {
    }
    pclose(p);
    char *mark = strstr(out, "@@exit=");
    return mark ? atoi(mark + 7) : -1;
}

/* ---- the table ---------------------------------------------------------------------------------- */

/* `args` follows `gomboc`; @CASE@ is the row's scene file (case.ini, holding `text`), @D@ the row's
 * directory. A row's message must hold every string of `must`. */
typedef struct bad_row {
    const char *args;
    const char *text;
    size_t text_len; /* 0: strlen(text) */
    int exit;
    const char *must[3];
} bad_row;

#define RUN "run @CASE@ --out @D@"
#define HULL_SCENE "[model]\ncontact = fast-grid\n[integrator]\nperiods = 1\n"
#define ATLAS_SCENE "[model]\nequation = rolling\ncontact = continuous\ncertificate = atlas\n[integrator]\nperiods = 1\n"
#define BYTES(s) s, sizeof(s) - 1

static const bad_row rows[] = {
    /* Misread or accepted before: each is a refusal now. */
    {RUN, "@LONG@", 0, 2, {"case.ini:1:", "bytes long", "at most 198 bytes a line"}},
    {RUN, "[forcing]\npsi = 0.1x\n", 0, 2, {"case.ini:2: [forcing] psi = 0.1x", "not an angle", "-1000 <= psi <= 1000 [rad]"}},
    {RUN, "[forcing]\npsi = pi/3junk\n", 0, 2, {"case.ini:2: [forcing] psi = pi/3junk", "not an angle", "p*pi/q"}},
    {RUN, "[model]\ngrid = 2x-18446744073709551613\n", 0, 2, {"case.ini:2: [model] grid", "not a grid", "NP*NT <= 67108864"}},
    {RUN, "[model]\ngrid = +8x +9\n", 0, 2, {"case.ini:2: [model] grid = +8x +9", "not a grid", "NT >= 3"}},
    {RUN, "[body]\nbeta = 0.1 # note\n", 0, 2, {"case.ini:2: [body] beta = 0.1 # note", "not a number", "0 <= beta < 0.25"}},
    {RUN, "[body]\nbeta = 0.1\nbeta = 0.2\n", 0, 2, {"case.ini:3: [body] beta = 0.2", "given twice (first at line 2", "each key once"}},
    {RUN, "[body]\nbeta = 0.1\n  mass = 2\n", 0, 2, {"case.ini:3:", "indented line", "continuation lines are not read"}},
    {RUN, BYTES("[body]\nbeta = 0.1\0 9\n"), 2, {"case.ini:2:", "NUL byte at column 11", "without NUL bytes"}},
    {RUN, "[scene]\ndescription = caf\xe9\n", 0, 2, {"case.ini:2:", "byte 0xE9 at column 18 is not UTF-8", "allowed: UTF-8 text"}},
    {RUN, "[scene]\ndescription = \x1b[31mred\n", 0, 2, {"case.ini:2:", "control character U+001B", "printable text and TAB"}},
    {RUN, "[scene]\ndescription = a\rb\n", 0, 2, {"case.ini:2:", "control character U+000D", "printable text"}},
    {RUN, "[scene]\ndescription = \xc2\x9b" "31m\n", 0, 2, {"case.ini:2:", "control character U+009B", "printable text"}},
    {RUN, "[scene]\ndescription = \xed\xa0\x80\n", 0, 2, {"case.ini:2:", "not UTF-8", "UTF-8 text"}},
    {RUN, "[scene]\ndescription = \xc0\xaf\n", 0, 2, {"case.ini:2:", "byte 0xC0", "UTF-8 text"}},
    /* Finite values that overflowed later: refused by the reader with their physical range. */
    {RUN, "[forcing]\nomega = 1e-300\n", 0, 2, {"case.ini:2: [forcing] omega = 1e-300", "out of range", "0.01 <= omega <= 10000 [rad/s]"}},
    {RUN, "[forcing]\ng = 1e308\n", 0, 2, {"case.ini:2: [forcing] g = 1e308", "out of range", "0 <= g <= 1000 [m/s2]"}},
    {RUN, "[model]\ndamping = 1e300\n", 0, 2, {"case.ini:2: [model] damping", "out of range", "0 <= damping <= 1000 [N m s]"}},
    {RUN, "[model]\nfriction = 0\n", 0, 2, {"case.ini:2: [model] friction", "out of range", "0 < friction <= 1000"}},
    {RUN, "[model]\nfriction = nan\n", 0, 2, {"case.ini:2: [model] friction", "", "0 < friction <= 1000"}},
    {RUN, "[model]\nfriction = -0.2\n", 0, 2, {"case.ini:2: [model] friction", "out of range", "rough, or 0 < friction <= 1000"}},
    {RUN, "[model]\nfriction = smooth\n", 0, 2, {"case.ini:2: [model] friction", "smooth", "rough, or 0 < friction <= 1000"}},
    {RUN, "[model]\nfriction = 0.3\n", 0, 2, {"case.ini:2: [model] friction", "contact_law = held: a held contact never slips",
                                              "allowed: rough with either held or unilateral; a finite mu with contact_law = unilateral"}},
    {RUN, "[model]\ncontact = continuous\nequation = rolling\ncontact_law = unilateral\nrestitution = 1.5\n[integrator]\nlocate_switches = yes\n", 0, 2, {"case.ini:5: [model] restitution", "out of range", "0 <= restitution <= 1"}},
    {RUN, "[model]\nrestitution = -0.1\n", 0, 2, {"case.ini:2: [model] restitution", "out of range", "0 <= restitution <= 1"}},
    /* the compliant law's own keys (its row's, read by the scene table) */
    {RUN, "[model]\nstiffness = 1e6\n", 0, 2, {"case.ini:2: [model] stiffness", "needs [model] contact_law = compliant", "allowed: with that law only"}},
    {RUN, "[model]\ncontact_law = compliant\nfriction = 0.5\nstiffness = 0\n[integrator]\nlocate_switches = yes\n", 0, 2, {"case.ini:4: [model] stiffness = 0", "out of range", "0 < stiffness <= 1e+15 [N/m^exponent]"}},
    {RUN, "[model]\ncontact_law = compliant\nfriction = 0.5\nexponent = 0.5\n[integrator]\nlocate_switches = yes\n", 0, 2, {"case.ini:4: [model] exponent = 0.5", "out of range", "1 <= exponent <= 3"}},
    {RUN, "[model]\ncontact_law = compliant\n[integrator]\nlocate_switches = yes\n", 0, 2, {"[model] friction (default)", "contact_law = compliant: its friction is Coulomb's, regularised, and needs a finite mu", "a finite mu with contact_law = unilateral or compliant"}},
    {RUN, "[model]\ncontact_law = compliant\nfriction = 0.5\nrestitution = 0.5\n[integrator]\nlocate_switches = yes\n", 0, 2, {"case.ini:4: [model] restitution", "contact_law = compliant", "allowed: the default, 0, with contact_law = compliant"}},
    {RUN, "[model]\ncontact_law = compliant\nfriction = 0.5\n[integrator]\nlocate_switches = no\n", 0, 2, {"case.ini:5: [integrator] locate_switches = no", "every change of the lowest point is located", "allowed: yes with contact_law = compliant"}},
    {RUN, "[model]\nrestitution = nan\n", 0, 2, {"case.ini:2: [model] restitution", "", "0 <= restitution <= 1"}},
    {RUN, "[model]\nrestitution = 0.5\n", 0, 2, {"case.ini:2: [model] restitution: with [model] contact_law = held", "never leaves the plane", "allowed: the default, 0, with contact_law = held"}},
    {RUN, "[initial]\nheight = 0.1\n", 0, 2, {"case.ini:2: [initial] height: with [model] contact_law = held", "never leaves the plane", "any value in range with unilateral"}},
    {RUN, "[initial]\nvelocity = 0, 0, 1\n", 0, 2, {"case.ini:2: [initial] velocity: with [model] contact_law = held", "", "allowed: the default, 0"}},
    {RUN, "[initial]\nheight = -1\n", 0, 2, {"case.ini:2: [initial] height", "out of range", "0 <= height <= 1000000"}},
    {RUN, "[initial]\nomega = 1e308,0,0\n", 0, 2, {"case.ini:2: [initial] omega", "out of range", "-1000 <= each component <= 1000 [rad/s]"}},
    {RUN, "[forcing]\nA2 = 1e308\n", 0, 2, {"case.ini:2: [forcing] A2", "out of range", "-1000 <= A2 <= 1000"}},
    {RUN, "[body]\nmass = 1e-300\n", 0, 2, {"case.ini:2: [body] mass", "out of range", "1e-06 <= mass <= 1000000 [kg]"}},
    {RUN, "[body]\nbeta = 1e999\n", 0, 2, {"case.ini:2: [body] beta = 1e999", "beyond the range of a double", "0 <= beta < 0.25"}},
    {RUN, "[forcing]\npsi = 1e400\n", 0, 2, {"case.ini:2: [forcing] psi", "beyond the range of a double", "psi <= 1000"}},
    /* Messages that contradicted their own ranges. */
    {RUN, "[integrator]\nsteps_per_period = 1e8\n", 0, 2, {"case.ini:2: [integrator] steps_per_period = 1e8", "not an integer", "an integer from 1 to 100000000"}},
    {RUN, "[integrator]\nsteps_per_period = 100000001\n", 0, 2, {"steps_per_period = 100000001", "out of range", "an integer from 1 to 100000000"}},
    {RUN, "[output]\nsample_every = 0\n", 0, 2, {"case.ini:2: [output] sample_every = 0", "out of range", "an integer from 1 to 100000000"}},
    {RUN, "[output]\nsample_every = 184467440737095516160\n", 0, 2, {"[output] sample_every", "out of range", "an integer from 1 to 100000000"}},
    /* Every other kind of key and value. */
    {RUN, "[body]\n\nbeta = 0.25\n", 0, 2, {"case.ini:3: [body] beta = 0.25", "out of range", "0 <= beta < 0.25"}},
    {RUN, "[body]\nbeta = nan\n", 0, 2, {"[body] beta = nan", "not a number", "0 <= beta < 0.25"}},
    {RUN, "[body]\nbeta = 0x1p-3\n", 0, 2, {"[body] beta = 0x1p-3", "not a number", "0 <= beta"}},
    {RUN, "[body]\nbeta =\n", 0, 2, {"case.ini:2: [body] beta = ", "not a number", "0 <= beta"}},
    {RUN, "[body]\nmorphology = III\n", 0, 2, {"case.ini:2: [body] morphology = III", "unknown", "allowed: I, II"}},
    {RUN, "[body]\nmorphology = I\ncolour = red\n", 0, 2, {"case.ini:3: [body] colour = red: unknown key", "allowed in [body]: morphology, beta, mesh, r, chi, mass", ""}},
    {RUN, "[bdoy]\nbeta = 0.1\n", 0, 2, {"case.ini:1: unknown section [bdoy]", "allowed: scene, body, forcing", ""}},
    {RUN, "[body]\nbeta = 0.1\n[forcing]\n[body]\nmass = 2\n", 0, 2, {"case.ini:4: [body] again (first at line 1", "each section once", ""}},
    {RUN, "beta = 0.1\n", 0, 2, {"case.ini:1: beta = 0.1", "before any [section]", ""}},
    {RUN, "[body] beta = 0.2\n", 0, 2, {"case.ini:1: text after [body]", "a section header alone on its line", ""}},
    {RUN, "[body]\nmorphology I\n", 0, 2, {"case.ini:2: malformed line 'morphology I'", "allowed: [section], key = value", ""}},
    {RUN, "[body\nbeta = 0.1\n", 0, 2, {"case.ini:1: malformed line '[body'", "[section]", ""}},
    {RUN, "[model]\ncontact = magnetic\n", 0, 2, {"case.ini:2: [model] contact = magnetic", "unknown", "allowed: grid, fast-grid, continuous"}},
    {RUN, "[model]\nequation = newton\n", 0, 2, {"case.ini:2: [model] equation = newton", "unknown", "allowed: paper, rolling"}},
    {RUN, "[model]\nnodes = gauss\n", 0, 2, {"case.ini:2: [model] nodes = gauss", "unknown", "allowed: centred, linspace"}},
    {RUN, "[forcing]\namplitude_units = furlongs\n", 0, 2, {"case.ini:2: [forcing] amplitude_units = furlongs", "unknown", "allowed: m/s2, g"}},
    {RUN, "[integrator]\nmethod = rk8pd\n", 0, 2, {"case.ini:2: [integrator] method = rk8pd with [model] contact = fast-grid", "cannot cross the jumps", "allowed: rk4 with grid or fast-grid"}},
    {RUN, "[model]\ncontact = fast-grid\n[integrator]\nmethod = rkf45\n", 0, 2, {"case.ini:4: [integrator] method", "contact = fast-grid", "any method with contact = continuous"}},
    {RUN, "[model]\ncertificate = atlas\n", 0, 2, {"case.ini:2: [model] certificate = atlas with [model] contact = fast-grid", "only continuous contact is certified", "allowed: per-vertical with any contact; atlas or multi-start with contact = continuous"}},
    {RUN, "[model]\ncertificate = proof\n", 0, 2, {"case.ini:2: [model] certificate = proof", "unknown", "allowed: per-vertical, atlas"}},
    {RUN, "[integrator]\nmethod = euler\n", 0, 2, {"case.ini:2: [integrator] method = euler", "unknown", "allowed: rk4, rk8pd, rkf45, rk4imp"}},
    {RUN, "[integrator]\nsteps_per_period = -3\n", 0, 2, {"case.ini:2: [integrator] steps_per_period = -3", "not an integer", "1 to 100000000"}},
    {RUN, "[integrator]\nperiods = 0\n", 0, 2, {"case.ini:2: [integrator] periods = 0", "out of range", "0 < periods <= 10000000"}},
    {RUN, "[integrator]\nrtol = 1e-20\n", 0, 2, {"case.ini:2: [integrator] rtol", "out of range", "1e-15 <= rtol <= 0.1"}},
    {RUN, "[integrator]\nlocate_switches = maybe\n", 0, 2, {"case.ini:2: [integrator] locate_switches = maybe", "not a flag", "allowed: yes, no"}},
    {RUN, "[initial]\nattitude = axis-angle 0,0,0,1\n", 0, 2, {"case.ini:2: [initial] attitude = axis-angle 0,0,0,1", "out of range", "non-zero axis"}},
    {RUN, "[initial]\nattitude = axis-angle 1,0,0\n", 0, 2, {"case.ini:2: [initial] attitude", "not an attitude", "AX,AY,AZ,ANGLE"}},
    {RUN, "[initial]\nomega = 1,2\n", 0, 2, {"case.ini:2: [initial] omega = 1,2", "not three numbers", "X,Y,Z"}},
    {RUN, "[diagnostics]\nspectrum = yes\n[spectrum]\nwindow = blackman\n", 0, 2, {"case.ini:4: [spectrum] window = blackman", "unknown", "allowed: rectangular, hann"}},
    {RUN, "[integrator]\nsteps_per_period = 4\n[diagnostics]\nstrobe = yes\n[strobe]\nphase = 0.3\n", 0, 2, {"case.ini:6: [strobe] phase = 0.3 is not on the sample grid", "a multiple of 1/4", ""}},
    {RUN, "[integrator]\nperiods = 10\n[diagnostics]\nlyapunov = yes\n[lyapunov]\ninterval_periods = 3\n", 0, 2, {"case.ini:6: [lyapunov] interval_periods = 3", "does not divide", "at least 2 intervals"}},
    {RUN, "[integrator]\nperiods = 10\n[diagnostics]\nlyapunov = yes\n[lyapunov]\nbatches = 20\n", 0, 2, {"case.ini:6: [lyapunov] batches = 20 exceeds the 5 intervals of the record after its longest warm-up", "2 <= batches <= intervals - warmup_intervals", ""}},
    {RUN, "[integrator]\nperiods = 10\n[diagnostics]\nlyapunov = yes\n[lyapunov]\nwarmup_intervals = 0\nbatches = 11\n", 0, 2, {"case.ini:7: [lyapunov] batches = 11 exceeds the 10 intervals", "allowed: chosen, or 2 <= batches", ""}},
    {RUN, "[integrator]\nperiods = 10\n[diagnostics]\nlyapunov = yes\n[lyapunov]\nwarmup_intervals = 5\n", 0, 2, {"case.ini:6: [lyapunov] warmup_intervals = 5 is not less than half the 10 intervals", "0 <= warmup_intervals < intervals / 2", ""}},
    {RUN, "[integrator]\nperiods = 10\n[diagnostics]\nlyapunov = yes\n[lyapunov]\ninterval_periods = 2\nwindow_periods = 3\n", 0, 2, {"case.ini:7: [lyapunov] window_periods = 3 is not a whole number of intervals of 2 periods", "a multiple of interval_periods up to periods - transient_periods", ""}},
    {RUN, "[integrator]\nperiods = 10\n[diagnostics]\nlyapunov = yes\n[lyapunov]\ntransient_periods = 2\nwindow_periods = 9\n", 0, 2, {"case.ini:7: [lyapunov] window_periods = 9 is not a whole number of intervals of 1 periods within the record of 8 periods", "allowed: 0 for no windows", ""}},
    {RUN, "[lyapunov]\nwindow_periods = -1\n", 0, 2, {"case.ini:2: [lyapunov] window_periods = -1", "0", "10000000"}},
    {RUN, "[lyapunov]\nbatches = auto\n", 0, 2, {"case.ini:2: [lyapunov] batches = auto", "not an integer", "chosen (from the record), or an integer from 2 to 1000000"}},
    {RUN, "[lyapunov]\ndelta0 = 2\n", 0, 2, {"case.ini:2: [lyapunov] delta0 = 2", "out of range", "1e-15 <= delta0 <= 0.1"}},
    {RUN, "[lyapunov]\nomega_scale = -1\n", 0, 2, {"case.ini:2: [lyapunov] omega_scale = -1", "out of range", "0.001 <= omega_scale <= 1000000 [rad/s]"}},
    {RUN, "[integrator]\nperiods = 5\n[diagnostics]\nstrobe = yes\n[strobe]\ntransient_periods = 5\n", 0, 2, {"case.ini:6: [strobe] transient_periods = 5 leaves no strobe samples", "< [integrator] periods = 5", ""}},
    {"lyapunov @CASE@", "[integrator]\nperiods = 10\n[lyapunov]\nbatches = 20\n", 0, 2, {"case.ini:4: [lyapunov] batches = 20 exceeds", "2 <= batches <= intervals - warmup_intervals", ""}},
    /* Scan files (gomboc scan): the same strict reader, their own keys. */
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\nperiod = 10\n", 0, 2, {"case.ini:3: [scan] period = 10: unknown key", "allowed in [scan]: description, base, periods, transient_periods, metrics, failed_points, atlas, atlas_file, hand_over", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\n[x]\nkey = forcing.omega\nfrom = 20\nto = 10\ncount = 5\n[y]\nkey = forcing.A1\nfrom = 1\nto = 2\ncount = 2\n", 0, 2, {"case.ini:6: [x] to = 10: an empty range", "to > from = 20", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\nmetrics = omega_rms, bogus\n", 0, 2, {"case.ini:3: [scan] metrics = omega_rms, bogus: unknown metric 'bogus'", "omega_rms, switch_rate, strobe_sd, mean_height, monitors, lambda", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\n[x]\nkey = integrator.periods\n", 0, 2, {"case.ini:4: [x] key = integrator.periods: set by the scan on every point", "allowed: a key of [body]", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\n[x]\ncount = 0\n", 0, 2, {"case.ini:4: [x] count = 0: out of range", "an integer from 1 to 10000", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\n[x]\nkey = forcing.omega\nfrom = 10\nto = 20\ncount = 3\n", 0, 2, {"[y] key is missing", "Scan files", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\n[x]\nkey = forcing.omega\nfrom = 10\nto = 20\ncount = 3\n[y]\nkey = forcing.omega\nfrom = 1\nto = 2\ncount = 2\n", 0, 2, {"case.ini:9: [y] key = forcing.omega: the same key as [x]", "two different keys", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = nothing.ini\n[x]\nkey = forcing.omega\nfrom = 10\nto = 20\ncount = 3\n[y]\nkey = forcing.A1\nfrom = 1\nto = 2\ncount = 2\n", 0, 2, {"case.ini:2: [scan] base = ", "nothing.ini: cannot open the case file", "a relative base is read from the scan file's directory"}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\n[z]\n", 0, 2, {"case.ini:3: unknown section [z]", "allowed: scan, x, y", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\natlas = always\n", 0, 2, {"case.ini:3: [scan] atlas = always: unknown", "allowed: none, shared", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\nhand_over = always\n", 0, 2, {"case.ini:3: [scan] hand_over = always: unknown", "allowed: none, time-stepping", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\nhand_over = none\nhand_over = none\n", 0, 2, {"case.ini:4: [scan] hand_over = none: given twice", "first at line 3", ""}},
    /* the ninth [scan] key has its own place among the keys seen: the [x] axis after it is read, and judged on its range */
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\nhand_over = none\n[x]\nkey = forcing.omega\nfrom = 20\nto = 10\ncount = 5\n[y]\nkey = forcing.A1\nfrom = 1\nto = 2\ncount = 2\n", 0, 2, {"case.ini:7: [x] to = 10: an empty range", "to > from = 20", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\n[x]\nkey = omega\n", 0, 2, {"case.ini:4: [x] key = omega: not a scene key", "SECTION.KEY", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\ntransient_periods = 100\n[x]\nkey = forcing.omega\nfrom = 10\nto = 20\ncount = 3\n[y]\nkey = forcing.A1\nfrom = 1\nto = 2\ncount = 2\n", 0, 2, {"case.ini:3: [scan] transient_periods = 100 leaves less than one period", "periods - 1 = 99", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\n[x]\nkey = forcing.omega\nscale = random\nseed = 1\ncount = 4\n[y]\nkey = forcing.A1\nfrom = 1\nto = 2\ncount = 2\n", 0, 2, {"[x] key = forcing.omega with scale = random", "initial.attitude with scale = random and a seed", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\n[x]\nkey = initial.attitude\nscale = random\nfrom = 0\ncount = 4\nseed = 1\n[y]\nkey = forcing.A1\nfrom = 1\nto = 2\ncount = 2\n", 0, 2, {"[x] a random axis takes count and seed, not from or to", "", ""}},
    {"scan @CASE@ --out @D@ --threads 0", "[scan]\n", 0, 2, {"--threads '0' is out of range", "(allowed: an integer from 1 to 256)", ""}},
    {"scan @CASE@ --out @D@ --json", "[scan]\n", 0, 2, {"unknown option '--json'", "--out, --resume, --threads", ""}},
    {"scan --out @D@", NULL, 0, 2, {"missing SCAN", "a scan file", ""}},
    /* gomboc prove (run as gomboc-prove beside the command): its options, and --morphology for the horseshoes only. */
    {"prove --precision 32", NULL, 0, 2, {"--precision '32' is out of range", "(allowed: an integer from 64 to 4096)", ""}},
    {"prove --depth 1.5", NULL, 0, 2, {"--depth 1.5: not an integer", "(allowed: an integer from 1 to 40)", ""}},
    {"prove --horseshoe --horseshoe", NULL, 0, 2, {"option '--horseshoe' is given twice", "allowed: each option once", ""}},
    {"prove --morphology I", NULL, 0, 2, {"--morphology I without --horseshoe", "allowed: --morphology with --horseshoe only", ""}},
    {"prove --horseshoe --morphology III", NULL, 0, 2, {"--morphology III: no horseshoe for it", "allowed: I or II", ""}},
    {"prove --large-trellis --horseshoe", NULL, 0, 2, {"--large-trellis with --horseshoe", "allowed: one of them", ""}},
    {"prove --large-trellis --large-trellis", NULL, 0, 2, {"option '--large-trellis' is given twice", "allowed: each option once", ""}},
    /* gomboc melnikov: the reduced model needs a saddle. */
    {"melnikov @CASE@", "[body]\nbeta = 0\n", 0, 2, {"beta = 0: a sphere has no unstable equilibrium", "0 < beta < 0.25", ""}},
    {"melnikov @CASE@", "[forcing]\ng = 0\n", 0, 2, {"[forcing] g = 0", "no saddle", "g > 0"}},
    {"melnikov @CASE@ --mass heavy", "[body]\nbeta = 0.1\n", 0, 2, {"--mass heavy: unknown", "allowed: top, variable", ""}},
    {"melnikov @CASE@ --weight p", "[body]\nbeta = 0.1\n", 0, 2, {"--weight p: unknown", "allowed: exact, paper", ""}},
    {"melnikov @CASE@ --damping viscous", "[body]\nbeta = 0.1\n", 0, 2, {"--damping viscous: unknown", "allowed: paper, exact", ""}},
    {"melnikov @CASE@ --curve @D@/c.csv --curve-points 1", "[body]\nbeta = 0.1\n", 0, 2, {"--curve-points '1' is out of range", "(allowed: an integer from 2 to 1000)", ""}},
    {"melnikov @CASE@ --curve @D@/sub", "[body]\nbeta = 0.1\n", 0, 2, {"--curve", "is not a regular file", ""}},
    {"melnikov @CASE@ --tangle 0.5", "[body]\nbeta = 0.1\n", 0, 2, {"--tangle '0.5' is out of range", "(allowed: a spacing from 1e-4 to 0.1)", ""}},
    {"melnikov @CASE@ --tangle", "[body]\nbeta = 0.1\n", 0, 2, {"--tangle", "", ""}},
    {"melnikov @CASE@ --tangle-threshold 5", "[body]\nbeta = 0.1\n", 0, 2, {"--tangle-threshold 5 without --tangle", "allowed: --tangle-threshold with --tangle SPACING", ""}},
    {"melnikov @CASE@ --tangle 0.02 --tangle-threshold 31", "[body]\nbeta = 0.1\n", 0, 2, {"--tangle-threshold '31' is out of range", "(allowed: an integer from 1 to 30)", ""}},
    {"melnikov @CASE@ --mass variable --tangle 0.02", "[body]\nbeta = 0.1\n", 0, 2, {"--tangle 0.02 with --mass variable", "there is no separatrix", "allowed: --tangle with --mass top"}},
    /* The case file itself, and the output directory. */
    {"run @D@", NULL, 0, 2, {"not a regular file", "allowed: a scene file", ""}},
    {"lyapunov @D@", NULL, 0, 2, {"not a regular file", "allowed: a scene file", ""}},
    {"run @D@/missing.ini", NULL, 0, 2, {"missing.ini: cannot open the case file", "No such file", ""}},
    /* bodies of one's own: a mesh the scene names, an expression for r or chi */
    {RUN, "[body]\nmesh = missing.off\n", 0, 2, {"case.ini:2: [body] mesh", "missing.off", "allowed: a readable OFF, OBJ or STL file"}},
    {RUN, "[body]\nmesh = case.ini\n", 0, 2, {"case.ini:2: [body] mesh", "the mesh format is unknown", "allowed: a name ending .off, .obj or .stl"}},
    {RUN, "[body]\nmorphology = I\nchi = theta\n", 0, 2, {"case.ini:3: [body] chi", "with [body] morphology", "allowed: one of them"}},
    {RUN, "[body]\nchi = theta - 5*psi\n", 0, 2, {"case.ini:2: [body] chi", "names 'psi', which is unknown", "allowed: phi, theta, beta, pi, e"}},
    {RUN, "[body]\nr = (1 + \n", 0, 2, {"case.ini:2: [body] r", "does not parse", "allowed: an expression in phi, theta, beta"}},
    {RUN, "[body]\nr = cos(phi)\n", 0, 2, {"case.ini:2: [body] r", "makes r <= 0", "allowed: r > 0 on the whole sphere"}},
    {RUN, "[body]\nr = 1 + 0.1*sin(theta/2)\n", 0, 2, {"case.ini:2: [body] r", "is not one surface", "periodic in theta"}},
    {RUN, "[body]\nr = 1 + 1/sin(phi)\n", 0, 2, {"case.ini:2: [body] r", "is not finite", "allowed: a smooth, finite body"}},
    {RUN, "[body]\nr = 1.1 + cos(phi)\n[model]\ncontact = continuous\ncertificate = per-vertical\n", 0, 2, {"case.ini:5: [model] certificate = per-vertical", "interval enclosures", "allowed: multi-start"}},
    {RUN, "[body]\nr = 1.1 + cos(phi)\nbeta = 0.3\n", 0, 2, {"case.ini:3: [body] beta = 0.3", "out of range", "0 <= beta < 0.25"}},
    {"run @CASE@ --atlas @D@/a.atlas", "[body]\nbeta = 0.1\n", 0, 2, {"--atlas", "has no atlas", "allowed: a scene with [model] certificate = atlas"}},
    {"run @CASE@ --hull @D@/a.hull", "[model]\ncontact = grid\n", 0, 2, {"--hull", "has no hull", "allowed: a scene with [model] contact = fast-grid"}},
    {"run @CASE@ --out @D@/missing", "[body]\nbeta = 0.1\n", 0, 2, {"--out", "missing' does not exist", "allowed: an existing, writable directory"}},
    /* the faults of several keys said at once, in the file's order; more than 8 counted */
    {"run @CASE@ --out @D@", "[body]\nbeta = 0.9\nmass = -1\n[forcing]\nomega = abc\nfoo = 1\n", 0, 2,
     {"case.ini:2: [body] beta = 0.9: out of range", "case.ini:3: [body] mass = -1: out of range",
      "case.ini:6: [forcing] foo = 1: unknown key"}},
    {"run @CASE@ --out @D@", "[forcing]\na = 1\nb = 1\nc = 1\nd = 1\ne = 1\nf = 1\ng = x\nh = 1\ni = 1\nj = 1\n", 0, 2,
     {"case.ini:2: [forcing] a = 1: unknown key", "case.ini:9: [forcing] h = 1: unknown key", "10 faults in all, the first 8 said"}},
    {"run @CASE@ --out @D@/keep.txt", "[body]\nbeta = 0.1\n", 0, 2, {"--out", "is not a directory", "allowed: an existing, writable directory"}},
    {"run @CASE@ --out", "[body]\nbeta = 0.1\n", 0, 2, {"option '--out' needs a value", "", ""}},
    {"run @CASE@ @CASE@", "[body]\nbeta = 0.1\n", 0, 2, {"a second case file", "allowed: one CASE", ""}},
    {"run", NULL, 0, 2, {"missing CASE", "allowed: a scene file", ""}},
    /* Options. */
    {"shape --morphology I --beta 0.25", NULL, 0, 2, {"--beta '0.25' is out of range", "0 <= beta < 0.25", ""}},
    {"shape --morphology II --beta 0.3", NULL, 0, 2, {"--beta '0.3' is out of range", "0 <= beta < 0.25", ""}},
    {"shape --morphology I --beta -0.01", NULL, 0, 2, {"--beta '-0.01' is out of range", "0 <= beta < 0.25", ""}},
    {"shape --morphology I --beta abc", NULL, 0, 2, {"--beta 'abc' is not a number", "0 <= beta < 0.25", ""}},
    {"shape --morphology I --beta 0.1x", NULL, 0, 2, {"--beta '0.1x' is not a number", "0 <= beta < 0.25", ""}},
    {"shape --morphology I --beta nan", NULL, 0, 2, {"--beta 'nan' is not a number", "0 <= beta", ""}},
    {"shape --morphology I --beta ' 0.1'", NULL, 0, 2, {"--beta ' 0.1' is not a number", "0 <= beta", ""}},
    {"shape --morphology I --beta 1e999", NULL, 0, 2, {"--beta '1e999' is beyond the range of a double", "0 <= beta", ""}},
    {"shape --morphology III --beta 0.1", NULL, 0, 2, {"--morphology 'III' is unknown", "allowed: I, II", ""}},
    {"shape --morphology I --beta 0.1 --colour red", NULL, 0, 2, {"unknown option '--colour'", "allowed: --morphology", ""}},
    {"shape --morphology I --beta", NULL, 0, 2, {"'--beta' needs a value", "", ""}},
    {"shape --morphology I", NULL, 0, 2, {"missing --beta", "0 <= beta < 0.25", ""}},
    {"shape --beta 0.1", NULL, 0, 2, {"missing --morphology", "allowed: I, II", ""}},
    {"shape --morphology I --beta 0.1 --mass 0", NULL, 0, 2, {"--mass '0' is out of range", "1e-06 <= mass <= 1000000 [kg]", ""}},
    {"shape --morphology I --beta 0.1 --mass 1e-300", NULL, 0, 2, {"--mass '1e-300' is out of range", "1e-06 <= mass", ""}},
    {"shape --morphology I --beta 0.02 --radial-map @D@/device", NULL, 0, 2, {"--radial-map", "device' exists and is not a regular file", "allowed: a new or regular file"}},
    {"shape --morphology I --beta 0.02 --radial-map @D@/link.csv", NULL, 0, 2, {"--radial-map", "link.csv' exists and is not a regular file", "allowed: a new or regular file"}},
    {"shape --morphology I --beta 0.02 --radial-map @D@/sub", NULL, 0, 2, {"--radial-map", "sub' exists and is not a regular file", "a directory, link, device or FIFO"}},
    {"shape --morphology I --beta 0.02 --radial-map @D@/missing/map.csv", NULL, 0, 2, {"--radial-map", "its directory does not exist", "in an existing, writable directory"}},
    {"shape --morphology I --beta 0.02 --radial-map ''", NULL, 0, 2, {"--radial-map '' is empty", "allowed: a new or regular file", ""}},
    {"shape --morphology I --beta 0.02 --grid-nodes @D@/sub", NULL, 0, 2, {"--grid-nodes", "sub' exists and is not a regular file", "a directory, link, device or FIFO"}},
    {"shape --morphology I --beta 0.02 --grid-nodes @D@/missing/nodes.csv", NULL, 0, 2, {"--grid-nodes", "its directory does not exist", "in an existing, writable directory"}},
    {"shape --morphology I --beta 0.02 --grid-nodes @D@/n.csv --radial-map @D@/n.csv", NULL, 0, 2, {"--grid-nodes", "is also the --radial-map file", "not an input or another output"}},
    {"melnikov @CASE@", "[body]\nchi = theta - 5*phi\n", 0, 2, {"the reduced model certifies", "has no interval enclosure", "allowed: a morphology of the paper"}},
    {"shape --scene @CASE@ --beta 0.1", "[body]\nbeta = 0.1\n", 0, 2, {"--scene names the body and its mass", "allowed: --scene FILE", ""}},
    {"shape --scene @CASE@", "[body]\nchi = theta - 5*psi\n", 0, 2, {"--scene", "case.ini:2: [body] chi", "allowed: phi, theta, beta"}},
    {"shape --scene @CASE@ --radial-map @D@/m.csv", "[body]\nmesh = case.ini\n", 0, 2, {"--scene", "[body] mesh", "allowed: a name ending .off, .obj or .stl"}},
    {"shape --mesh @D@/missing.off", NULL, 0, 2, {"--mesh", "missing.off", "allowed: a readable mesh file"}},
    {"shape --mesh @D@/sub", NULL, 0, 2, {"--mesh", "sub", "allowed"}},
    {"shape --mesh @CASE@", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n", 0, 2, {"the mesh format is unknown", "allowed: a name ending .off, .obj or .stl", ""}},
    {"shape --mesh @CASE@ --beta 0.1", "OFF\n", 0, 2, {"--mesh names the body", "allowed: --mesh FILE [--mass M] [--json]", ""}},
    {"shape --morphology I --beta 0.02 --json > @D@/full", NULL, 0, 1, {"gomboc shape: cannot write standard output", "No space left on device", ""}},
    {"contact --morphology I --beta 0.12 --zb 0,0,0 --method grid", NULL, 0, 2, {"--zb '0,0,0' is the zero vector", "not all zero", ""}},
    {"contact --morphology I --beta 0.12 --zb 0,0 --method grid", NULL, 0, 2, {"--zb '0,0' is not three numbers", "X,Y,Z", ""}},
    {"contact --morphology I --beta 0.12 --zb 1,2,nan --method grid", NULL, 0, 2, {"--zb '1,2,nan' is not three numbers", "X,Y,Z", ""}},
    {"contact --morphology I --beta 0.12 --zb 1e200,0,0 --method grid", NULL, 0, 2, {"--zb '1e200,0,0' is out of range", "-1e100 <= component <= 1e100", ""}},
    {"contact --morphology I --beta 0.12 --zb 1e400,0,0 --method grid", NULL, 0, 2, {"--zb '1e400,0,0' is beyond the range of a double", "-1e100 <= component", ""}},
    {"contact --morphology I --beta 0.25 --zb 0,0,1 --method grid", NULL, 0, 2, {"--beta '0.25' is out of range", "0 <= beta < 0.25", ""}},
    {"contact --morphology I --beta 0.12 --zb 0,0,1 --method simplex", NULL, 0, 2, {"--method 'simplex' is unknown", "allowed: grid, fast-grid, continuous", ""}},
    {"contact --morphology I --beta 0.12 --zb 0,0,1 --method grid --grid 1x180", NULL, 0, 2, {"--grid '1x180' is out of range", "NP >= 2", ""}},
    {"contact --morphology I --beta 0.12 --zb 0,0,1 --method grid --grid 90by180", NULL, 0, 2, {"--grid '90by180' is not a grid", "NPxNT with NP >= 2", ""}},
    {"contact --morphology I --beta 0.12 --zb 0,0,1 --method grid --grid 2x-18446744073709551613", NULL, 0, 2, {"--grid", "is not a grid", "NP*NT <= 67108864"}},
    {"contact --morphology I --beta 0.12 --zb 0,0,1 --method grid --nodes gauss", NULL, 0, 2, {"--nodes 'gauss' is unknown", "allowed: centred, linspace", ""}},
    {"contact --morphology I --beta 0.12 --zb 0,0,1 --method grid --zoom-halfwidth 2", NULL, 0, 2, {"--zoom-halfwidth '2' is out of range", "0 < W <= 1", ""}},
    {"contact --morphology I --beta 0.12 --zb 0,0,1", NULL, 0, 2, {"missing --method", "allowed: grid, fast-grid, continuous", ""}},
    {"contact --morphology I --beta 0.12 --method grid", NULL, 0, 2, {"missing --zb", "not all zero", ""}},
    {"contact --morphology I --beta 0.12 --zb 0,0,1 --method grid --speed 3", NULL, 0, 2, {"unknown option '--speed'", "allowed: --morphology", ""}},
    {"contact --morphology I --beta 0.12 --zb 0,0,1 --method grid --landscape @D@/A.csv --zoom @D@/missing/B.csv", NULL, 0, 2,
     {"--zoom", "its directory does not exist", "in an existing, writable directory"}},
    {"contact --morphology I --beta 0.12 --zb 0,0,1 --method grid --landscape @D@/A.csv --zoom @D@/A.csv", NULL, 0, 2,
     {"--zoom", "is also the --landscape file", "not an input or another output of this run"}},
    /* Bad input, round 2: no output may destroy an input, a device or another run's work. The defects
     * found by a hostile review, by their number there: (1) an output that is an input; (2) a device
     * replaced, a link followed (test_outputs: FILE.tmp); (3) concurrent atlas writers (test_outputs);
     * (4) targets found bad only after the run; (5, 6) journals trusted (s8_scan.c); (7) a FIFO
     * waited on; (8) the scan JSON (s8_scan.c); (9) sets mixed by a kill (test_outputs); and the
     * smaller ones. */
    /* (1) */
    {"run @CASE@ --atlas @CASE@", ATLAS_SCENE, 0, 2, {"--atlas '", "is also the CASE file", "not an input or another output of this run"}},
    {"melnikov @CASE@ --curve @CASE@", "[body]\nbeta = 0.1\n", 0, 2, {"--curve '", "is also the CASE file", "not an input"}},
    /* (2), (4) */
    {"run @CASE@ --atlas @D@/device", ATLAS_SCENE, 0, 2, {"--atlas '", "device' exists and is not a regular file", "a new or regular file"}},
    {"run @CASE@ --atlas @D@/fifo", ATLAS_SCENE, 0, 2, {"--atlas '", "fifo' exists and is not a regular file", "FIFO"}},
    {"run @CASE@ --atlas @D@/link.csv", ATLAS_SCENE, 0, 2, {"--atlas '", "link.csv' exists and is not a regular file", "link"}},
    {"run @CASE@ --atlas ''", ATLAS_SCENE, 0, 2, {"--atlas '' is empty", "allowed: a new or regular file", ""}},
    {"run @CASE@ --atlas @D@/sub", ATLAS_SCENE, 0, 2, {"--atlas '", "sub' exists and is not a regular file", "directory"}},
    {"run @CASE@ --atlas @D@/missing/a.atlas", ATLAS_SCENE, 0, 2, {"--atlas '", "its directory does not exist", "writable directory"}},
    {"run @CASE@ --hull @CASE@", HULL_SCENE, 0, 2, {"--hull '", "is also the CASE file", "not an input or another output of this run"}},
    {"run @CASE@ --hull @D@/device", HULL_SCENE, 0, 2, {"--hull '", "device' exists and is not a regular file", "a new or regular file"}},
    {"run @CASE@ --hull @D@/sub", HULL_SCENE, 0, 2, {"--hull '", "sub' exists and is not a regular file", "directory"}},
    {"run @CASE@ --hull @D@/a --atlas @D@/a", ATLAS_SCENE, 0, 2, {"--hull", "has no hull", "allowed: a scene with [model] contact = fast-grid"}},
    /* smaller: options given twice, --curve-points alone */
    {RUN, "[model]\ncontact_law = bouncy\n", 0, 2, {"case.ini:2: [model] contact_law = bouncy", "unknown", "allowed: held, unilateral"}},
    {RUN, "[model]\ncontact = continuous\ncontact_law = unilateral\n", 0, 2, {"case.ini:3: [model] contact_law = unilateral with [model] contact = continuous, equation = paper", "eq 44 makes and takes energy", "allowed: held with any model; unilateral with equation = rolling, or with a grid model"}},
    {RUN, "[model]\ncontact_law = unilateral\n[integrator]\nlocate_switches = no\n", 0, 2, {"case.ini:4: [integrator] locate_switches = no with [model] contact_law = unilateral", "every impact is located", "allowed: yes with contact_law = unilateral"}},
    {RUN, "[model]\ncontact = continuous\nequation = rolling\ncontact_law = unilateral\n[integrator]\nlocate_switches = no\n", 0, 2, {"case.ini:6: [integrator] locate_switches = no with [model] contact_law = unilateral", "allowed: yes with contact_law = unilateral", ""}},
    {RUN, "[output]\nimpacts = yes\n", 0, 2, {"case.ini:2: [output] impacts = yes with [model] contact_law = held", "a held contact has no impacts", "allowed: yes with contact_law = unilateral"}},
    /* a computation the rough plane cannot follow (exit 1): a lift-off where the body would slide first. Tilted and
     * rolling, the body's first lift-off (t = 0.053, before any impact) needs a friction force of 2 N: a margin no
     * rounding moves, where Table 1's attitude at rest met such a lift-off only after 87 periods of chaotic motion */
    {RUN, "[forcing]\namplitude_units = g\n[model]\ncontact = continuous\nequation = rolling\ncontact_law = unilateral\n"
          "restitution = 0.5\n[integrator]\nperiods = 1\nsteps_per_period = 640\nlocate_switches = yes\n"
          "[initial]\nattitude = axis-angle 1,1,0,0.9\nomega = 5,0,0\n", 0, 1,
     {"lift-off at t = ", "the body slides before it lifts", "[model] friction = mu follows it"}},
    /* a computation that diverged (exit 1, not 2: the input was valid): RK4 at one step a period against a damping
     * rate c/I of ~2500 /s */
    {RUN, "[body]\nbeta = 0.12\n[model]\ncontact = continuous\nequation = rolling\ndamping = 1000\n[integrator]\n"
          "periods = 2\nsteps_per_period = 1\n[initial]\nomega = 1,0,0\n", 0, 1,
     {"t = 0.698131701: the state is no longer finite", "the integration diverged", "damping c over the inertia"}},
    {"run @CASE@ --out @D@ --out @D@", "[body]\nbeta = 0.1\n", 0, 2, {"option '--out' is given twice", "allowed: each option once", ""}},
    {"run @CASE@ --atlas @D@/a --atlas @D@/b", ATLAS_SCENE, 0, 2, {"option '--atlas' is given twice", "each option once", ""}},
    {"run @CASE@ --hull @D@/a --hull @D@/b", HULL_SCENE, 0, 2, {"option '--hull' is given twice", "each option once", ""}},
    {"melnikov @CASE@ --curve-points 5", "[body]\nbeta = 0.1\n", 0, 2, {"--curve-points 5 without --curve", "allowed: --curve-points with --curve FILE", ""}},
    {"melnikov @CASE@ --curve @D@/a.csv --curve @D@/b.csv", "[body]\nbeta = 0.1\n", 0, 2, {"option '--curve' is given twice", "", ""}},
    /* (7) */
    {"run @D@/fifo", NULL, 0, 2, {"fifo: not a regular file", "allowed: a scene file", ""}},
    {"scan @D@/fifo --out @D@", NULL, 0, 2, {"fifo: not a regular file", "allowed: a scan file", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = fifo\n[x]\nkey = forcing.omega\nfrom = 10\nto = 20\ncount = 2\n[y]\nkey = forcing.A1\nfrom = 1\nto = 2\ncount = 2\n", 0, 2,
     {"case.ini:2: [scan] base = ", "fifo: not a regular file", "allowed: a scene file"}},
    /* smaller: a text key as an axis, 10^8 points, --help to a full device */
    {"scan @CASE@ --out @D@", "[scan]\nbase = case.ini\n[x]\nkey = scene.description\nfrom = 1\nto = 2\ncount = 2\n", 0, 2,
     {"case.ini:4: [x] key = scene.description: not a key that takes one number", "allowed: a numeric key", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = case.ini\n[x]\nkey = forcing.omega\nfrom = 10\nto = 20\ncount = 10000\n[y]\nkey = forcing.A1\nfrom = 1\nto = 2\ncount = 10000\n", 0, 2,
     {"case.ini:12: [y] count = 10000: 10000 x 10000 points", "allowed: at most 1000000 points in all", ""}},
    {"--help > @D@/full", NULL, 0, 1, {"gomboc: cannot write standard output", "No space left on device", ""}},
    {"frobnicate", NULL, 0, 2, {"unknown command 'frobnicate'", "allowed: shape, contact, run, lyapunov", ""}},
    {"", NULL, 0, 2, {"usage: gomboc", "", ""}},
    /* Bad input, round 3, by the number of its defect. (1) A cache named like an output the run removes as
     * stale (the scene asks for no λ): */
    {RUN " --hull @D@/case-lyapunov.csv", HULL_SCENE, 0, 2, {"--hull '", "case-lyapunov.csv' is also the --out file", "a name this run removes as a stale output"}},
    {RUN " --atlas @D@/case-lyapunov.csv", ATLAS_SCENE, 0, 2, {"--atlas '", "case-lyapunov.csv' is also the --out file", "a name this run removes as a stale output"}},
    /* (2) A cache over a file that is not a cache of its kind: */
    {RUN " --hull @D@/keep.txt", HULL_SCENE, 0, 2, {"--hull '", "keep.txt' exists and is not a hull file", "allowed: a new file, or a hull file this command wrote"}},
    {RUN " --atlas @D@/keep.txt", ATLAS_SCENE, 0, 2, {"--atlas '", "keep.txt' exists and is not an atlas file", "allowed: a new file, or an atlas file"}},
    /* (9) An empty scene, and one of comments alone: */
    {RUN, "", 0, 2, {"case.ini: no [section] in 0 bytes", "an empty file", "allowed: at least one [section]"}},
    {RUN, "; a comment\n\n# another\n", 0, 2, {"case.ini: no [section] in 23 bytes", "only blank lines and comments", ""}},
    /* (12) An option's value that is an option: */
    {RUN " --hull --json", HULL_SCENE, 0, 2, {"option '--hull' needs a value, and '--json' is an option", "allowed: --hull VALUE, or --hull=VALUE", ""}},
    {"scan @CASE@ --out @D@ --atlas --resume", "[scan]\n", 0, 2, {"option '--atlas' needs a value, and '--resume' is an option", "--atlas=VALUE", ""}},
    {"run --out --json @CASE@", HULL_SCENE, 0, 2, {"option '--out' needs a value", "'--json' is an option", ""}},
    /* (13) A flag given twice: */
    {RUN " --json --json", HULL_SCENE, 0, 2, {"option '--json' is given twice", "allowed: each option once", ""}},
    {"scan @CASE@ --out @D@ --resume --resume", "[scan]\n", 0, 2, {"option '--resume' is given twice", "each option once", ""}},
    {"contact --morphology I --beta 0.12 --zb 0,0,1 --method grid --json --json", NULL, 0, 2, {"option '--json' is given twice", "", ""}},
    /* (17) A cache named like a temporary of the program: */
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\natlas = shared\natlas_file = .gomboc-999999-AAAAAA\n", 0, 2,
     {"case.ini:4: [scan] atlas_file = .gomboc-999999-AAAAAA: not a file name", "not named like the program's temporaries", ""}},
    {RUN " --hull @D@/.gomboc-999999-AAAAAA", HULL_SCENE, 0, 2, {"--hull '", "is named like a temporary of this program", ""}},
    {RUN " --atlas @D@/.gomboc-1-abcdef", ATLAS_SCENE, 0, 2, {"--atlas '", "is named like a temporary of this program", ""}},
    /* (19) Messages that named their key badly, or no range: */
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\n[x]\nkey = forcing.omega\nfrom = nan\nto = 2\ncount = 2\n", 0, 2,
     {"case.ini:5: [x] from = nan: not a number", "allowed: -1000000 <= from <= 1000000", ""}},
    {"contact --morphology I --beta 0.12 --zb 0,0,1e-320 --method grid", NULL, 0, 2, {"--zb '0,0,1e-320' is too short to give a direction", "of length at least 1e-100", ""}},
    {RUN, "[body]\nbeta : 0.1\n", 0, 2, {"case.ini:2: 'beta : 0.1': a key and its value separated by ':'", "allowed: key = value", ""}},
    {"scan @CASE@ --out @D@", "[scan]\nbase = x.ini\nperiods = 5\n[x]\nkey = forcing.omega\nfrom = 10\nto = 20\ncount = 3\n[y]\nkey = forcing.A1\nfrom = 1\nto = 2\ncount = 2\n", 0, 2,
     {"case.ini: [scan] transient_periods (default) = 20 leaves less than one period", "allowed: <= periods - 1 = 4", ""}},
};

/* Replace every @CASE@ and @D@ in `args` (malloc'd result). */
static char *expand(const char *args, const char *dir)
{
    size_t cap = strlen(args) * 2 + 8 * strlen(dir) + 64, used = 0;
    char *out = malloc(cap);
    for (const char *p = args; *p;) {
        if (!strncmp(p, "@CASE@", 6)) used += (size_t)sprintf(out + used, "'%s/case.ini'", dir), p += 6;
        else if (!strncmp(p, "@D@", 3)) used += (size_t)sprintf(out + used, "%s", dir), p += 3;
        else out[used++] = *p++;
    }
    out[used] = '\0';
    return out;
}

void bad_input_write_bytes(const char *path, const char *text, size_t len)
{
    FILE *f = fopen(path, "wb");
    if (!f) return;
    fwrite(text, 1, len, f);
    fclose(f);
}

/* A fresh row directory: a file of its own, a symbolic link, a subdirectory, a device, a FIFO and a
 * full device (for the rows that name them), and the row's scene file. The devices are the row's own (a
 * null character device where mknod is allowed, else a FIFO; a full one): a binary that replaced one
 * would change the directory, and never a file of the system such as /dev/null. */
static void prepare(char *dir, const bad_row *row)
{
    if (gb_check_tempdir("bad", dir, GB_CHECK_TEMPDIR_SIZE)) return;
    char path[512];
    snprintf(path, sizeof path, "%s/keep.txt", dir);
    bad_input_write_bytes(path, "a file the command must leave alone\n", 36);
    snprintf(path, sizeof path, "%s/link.csv", dir);
    if (symlink("keep.txt", path) != 0) return;
    snprintf(path, sizeof path, "%s/sub", dir);
    mkdir(path, 0755);
    snprintf(path, sizeof path, "%s/device", dir);
    if (mknod(path, S_IFCHR | 0666, makedev(1, 3)) != 0) mkfifo(path, 0666);
    snprintf(path, sizeof path, "%s/fifo", dir);
    mkfifo(path, 0666);
    /* a device that is always full (as /dev/full): where mknod is not allowed, the rows that write to it
     * fail, and say so by their exit status */
    snprintf(path, sizeof path, "%s/full", dir);
    mknod(path, S_IFCHR | 0666, makedev(1, 7));
    if (!row->text) return;
    snprintf(path, sizeof path, "%s/case.ini", dir);
    if (!strcmp(row->text, "@LONG@")) {
        /* A comment longer than libinih's 200-byte buffer, with a key at its end: read as two lines,
         * the key would be applied. */
        char text[400];
        memset(text, 'x', sizeof text);
        memcpy(text, "; ", 2);
        const char *tail = " beta = 0.2\n";
        memcpy(text + 300, tail, strlen(tail));
        bad_input_write_bytes(path, text, 300 + strlen(tail));
        return;
    }
    bad_input_write_bytes(path, row->text, row->text_len ? row->text_len : strlen(row->text));
}

/* One bad input: `args` after `gomboc` with `env` (VAR=VALUE words, or NULL) in a fresh row directory holding the
 * scene `text` (or none) and, when `file_name` is given, that file with `file_len` bytes of `file_text` (0:
 * strlen). 1 when the exit status is `exit`, the message holds every string of `must` and the directory is as it
 * was; `out` (of `cap` bytes) gets the command's output. */
int bad_input_row(const char *args, const char *env, const char *text, size_t text_len, const char *file_name,
                  const char *file_text, size_t file_len, int exit, const char *const must[3], char *out, size_t cap)
{
    const bad_row row = {args, text, text_len, exit, {must[0], must[1], must[2]}};
    char dir[GB_CHECK_TEMPDIR_SIZE];
    prepare(dir, &row);
    if (file_name) {
        char path[256];
        snprintf(path, sizeof path, "%s/%s", dir, file_name);
        bad_input_write_bytes(path, file_text, file_len ? file_len : strlen(file_text));
    }
    char *before = bad_input_snapshot(dir), *expanded = expand(args, dir), *environment = expand(env ? env : "", dir);
    size_t size = strlen(bad_input_binary()) + strlen(expanded) + strlen(environment) + 16;
    char *command = malloc(size);
    snprintf(command, size, "%s%s %s %s", env ? "env " : "", environment, bad_input_binary(), expanded);
    free(environment);
    const int code = bad_input_run_in(dir, command, out, cap);
    char *after = bad_input_snapshot(dir);
    int named = 1;
    for (int m = 0; m < 3; m++)
        if (must[m] && must[m][0] && !strstr(out, must[m])) named = 0;
    const int unchanged = !strcmp(before, after);
    free(before), free(after), free(expanded), free(command);
    gb_check_tempdir_remove(dir);
    return code == exit && named && unchanged;
}

static void test_bad_input_table(void)
{
    size_t passed = 0;
    const size_t total = sizeof rows / sizeof rows[0];
    for (size_t k = 0; k < total; k++) {
        const bad_row *row = &rows[k];
        static char out[16384];
        const int ok = bad_input_row(row->args, NULL, row->text, row->text_len, NULL, NULL, 0, row->exit, row->must, out, sizeof out);
        char q[400];
        snprintf(q, sizeof q, "gomboc %.200s%s%.60s", row->args, row->text ? " with case.ini = " : "",
                 row->text && strcmp(row->text, "@LONG@") ? row->text : row->text ? "(a 312-byte comment line)" : "");
        for (char *c = q; *c; c++)
            if ((unsigned char)*c < 0x20 || (unsigned char)*c >= 0x7F) *c = '?';
        gb_check c = {"-", "-", q, "exit status, message names the key or option and its range, directory unchanged", "exact"};
        passed += gb_check_true(&c, ok, "expected exit %d, the message's words and the directory unchanged: %.400s", row->exit, out);
    }
    gb_check cn = {"-", "-", "the table holds at least 60 bad inputs, and every one was refused as stated", "count", "exact"};
    gb_check_true(&cn, total >= 60 && passed == total, "%zu of %zu rows", passed, total);
}

/* A directory at least `length` characters deep below `dir` (made), its path in `out`. */
static void deep_directory(const char *dir, size_t length, char *out, size_t cap)
{
    snprintf(out, cap, "%s", dir);
    while (strlen(out) < length && strlen(out) + 52 < cap) {
        strcat(out, "/ppppppppppppppppppppppppppppppppppppppppppppppppp");
        mkdir(out, 0755);
    }
}

/* Valid input that a strict reader must still accept, and paths of any length. */
static void test_strict_but_fair(void)
{
    static const struct { const char *args, *text, *expect; } good[] = {
        {"shape --morphology I --beta 1e-320 --json", NULL, "\"beta\":\t9.99988867182683e-321"},
        {"run @CASE@ --out @D@ --json", "[body]\r\nbeta = 0.11\r\n[integrator]\r\nperiods = 1\r\nsteps_per_period = 20\r\n[model]\r\ncontact = fast-grid\r\n",
         "\"beta\":\t0.11"},
        {"run @CASE@ --out @D@ --json", "[initial]\nattitude = axis-angle 1e-320,1e-320,1e-320,1\n[integrator]\nperiods = 1\n"
         "steps_per_period = 20\n[model]\ncontact = fast-grid\n", "\"attitude\":\t\"axis-angle 1e-320,1e-320,1e-320,1\""},
        {"run @CASE@ --out @D@ --json", "\xEF\xBB\xBF[initial]\nomega = 1.3 , -0.7,\t0.4\n[forcing]\npsi = -2*pi/3\n[integrator]\nperiods = 1\nsteps_per_period = 20\n"
         "[model]\ncontact = fast-grid\n[scene]\ndescription = caf\xc3\xa9 \xe2\x80\x94 \"quoted\" ; an inline comment\n",
         "\"description\":\t\"caf\xc3\xa9 \xe2\x80\x94 \\\"quoted\\\"\","},
    };
    for (size_t k = 0; k < sizeof good / sizeof good[0]; k++) {
        const bad_row row = {good[k].args, good[k].text, 0, 0, {NULL, NULL, NULL}};
        char dir[GB_CHECK_TEMPDIR_SIZE];
        prepare(dir, &row);
        char *args = expand(good[k].args, dir);
        size_t size = strlen(bad_input_binary()) + strlen(args) + 4;
        char *command = malloc(size);
        snprintf(command, size, "%s %s", bad_input_binary(), args);
        static char out[1 << 16];
        const int code = bad_input_run_in(dir, command, out, sizeof out);
        char q[300];
        static const char *const why[] = {"a subnormal beta", "CRLF lines", "an axis of subnormal components",
                                          "BOM, spaced list, -2*pi/3, UTF-8 text with quotes, an inline ; comment stripped"};
        snprintf(q, sizeof q, "strict but fair: gomboc %s is accepted (%s)", good[k].args, why[k]);
        gb_check c = {"-", "-", q, "exit 0 and the value as written", "exact"};
        gb_check_true(&c, code == 0 && strstr(out, good[k].expect), "exit %d: %.300s", code, out);
        free(args), free(command);
        gb_check_tempdir_remove(dir);
    }

    /* An output directory 1190 characters deep and a case file of 240 characters: no path is cut. */
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("long", dir, sizeof dir)) return;
    char deep[1400];
    deep_directory(dir, 1180, deep, sizeof deep);
    char name[300];
    memset(name, 'n', 236);
    strcpy(name + 236, ".ini");
    char case_path[1800];
    snprintf(case_path, sizeof case_path, "%s/%s", dir, name);
    const char *scene = "[integrator]\nperiods = 1\nsteps_per_period = 20\n[model]\ncontact = fast-grid\n";
    bad_input_write_bytes(case_path, scene, strlen(scene));
    char command[4000], out[8192];
    snprintf(command, sizeof command, "%s run '%s' --out '%s'", bad_input_binary(), case_path, deep);
    const int code = bad_input_run_in(dir, command, out, sizeof out);
    char history[1800];
    snprintf(history, sizeof history, "%s/%.236s-history.csv", deep, name);
    gb_check cl = {"-", "-", "gomboc run into a 1190-character --out with a 240-character case name writes the full names",
                   "file system", "exact"};
    gb_check_true(&cl, code == 0 && access(history, F_OK) == 0, "exit %d, %zu-character output path: %.200s", code,
                  strlen(history), out);
    gb_check_tempdir_remove(dir);
}

/* A run writes NAME-* outputs only through temporaries ".gomboc-PID-XXXXXX": none may survive a
 * SIGTERM, and one left by a process killed outright is removed by the next command writing there. */
int bad_input_count_temporaries(const char *dir)
{
    int n = 0;
    DIR *d = opendir(dir);
    for (struct dirent *e; d && (e = readdir(d));) n += !strncmp(e->d_name, ".gomboc-", 8);
    if (d) closedir(d);
    return n;
}

static void test_temporaries(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("temp", dir, sizeof dir)) return;
    char case_path[320];
    snprintf(case_path, sizeof case_path, "%s/long.ini", dir);
    const char *scene = "[integrator]\nperiods = 100000\n[model]\ncontact = fast-grid\n";
    bad_input_write_bytes(case_path, scene, strlen(scene));
    const pid_t child = fork();
    if (child == 0) {
        bad_input_child_signals(0);
        freopen("/dev/null", "w", stderr);
        execl(bad_input_binary(), "gomboc", "run", case_path, "--out", dir, (char *)NULL);
        _exit(127);
    }
    int seen = 0;
    for (int k = 0; k < 200 && !seen; k++) { /* up to 10 s for the history's temporary to appear */
        seen = bad_input_count_temporaries(dir) > 0;
        if (!seen) usleep(50000);
    }
    kill(child, SIGTERM);
    int wstatus = 0;
    waitpid(child, &wstatus, 0);
    gb_check ct = {"-", "-", "SIGTERM during gomboc run: its temporary existed and is removed, no output appears", "file system", "exact"};
    char history[320];
    snprintf(history, sizeof history, "%s/long-history.csv", dir);
    gb_check_true(&ct, seen && WIFSIGNALED(wstatus) && WTERMSIG(wstatus) == SIGTERM && bad_input_count_temporaries(dir) == 0 &&
                       access(history, F_OK) != 0,
                  "temporary seen %d, signalled %d, temporaries left %d", seen, WIFSIGNALED(wstatus), bad_input_count_temporaries(dir));

    /* A temporary of a process that is gone (a child that has exited: its pid is free). */
    const pid_t gone = fork();
    if (gone == 0) _exit(0);
    waitpid(gone, NULL, 0);
    char stale[320], other[320];
    snprintf(stale, sizeof stale, "%s/.gomboc-%ld-Ab3dEf", dir, (long)gone);
    snprintf(other, sizeof other, "%s/.gomboc-notours", dir);
    bad_input_write_bytes(stale, "half", 4);
    bad_input_write_bytes(other, "not a temporary of ours", 23);
    const char *quick = "[integrator]\nperiods = 1\nsteps_per_period = 20\n[model]\ncontact = fast-grid\n";
    bad_input_write_bytes(case_path, quick, strlen(quick));
    char command[2 * 4096 + 1024], out[4096]; /* room for the binary's path (4096) and the two others whole */
    snprintf(command, sizeof command, "%s run '%s' --out '%s'", bad_input_binary(), case_path, dir);
    const int code = bad_input_run_in(dir, command, out, sizeof out);
    gb_check cs = {"-", "-", "a temporary left by a killed process is removed by the next run in its directory; other files stay",
                   "file system", "exact"};
    gb_check_true(&cs, code == 0 && access(stale, F_OK) != 0 && access(other, F_OK) == 0, "exit %d, stale %s, other %s", code,
                  access(stale, F_OK) ? "removed" : "LEFT", access(other, F_OK) ? "REMOVED" : "kept");
    gb_check_tempdir_remove(dir);
}

/* ---- the rule for every file written: inputs by identity, output sets, concurrent writers ---------- */

static int run_here(const char *dir, const char *args, char *out, size_t cap)
{
    char command[8192];
    snprintf(command, sizeof command, "%s %s", bad_input_binary(), args);
    return bad_input_run_in(dir, command, out, cap);
}

static void test_outputs(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("out", dir, sizeof dir)) return;
    char path[512], out[1 << 14];
    const char *atlas_scene = "[model]\nequation = rolling\ncontact = continuous\ncertificate = atlas\n[integrator]\nperiods = 1\n";
    snprintf(path, sizeof path, "%s/a.ini", dir);
    bad_input_write_bytes(path, atlas_scene, strlen(atlas_scene));

    /* A hard link to the scene is the scene: compared by device and inode, not by name. */
    char link_path[512];
    snprintf(link_path, sizeof link_path, "%s/same.atlas", dir);
    const int linked = link(path, link_path) == 0;
    char *before = gb_check_read_file(path);
    int code = run_here(dir, "run a.ini --atlas same.atlas", out, sizeof out);
    char *after = gb_check_read_file(path);
    gb_check ch = {"-", "-", "gomboc run a.ini --atlas L, L a hard link to a.ini", "exit 2 naming --atlas and CASE, the scene unchanged",
                   "exact"};
    gb_check_true(&ch, linked && code == 2 && strstr(out, "--atlas 'same.atlas' is also the CASE file 'a.ini'") && before && after &&
                       !strcmp(before, after), "exit %d: %.300s", code, out);
    free(before), free(after);
    remove(link_path);

    /* An output that exists as a directory is refused before the run: a scene of 10^5 periods would run
     * for minutes; the refusal comes at once, and nothing is written. */
    const char *long_scene = "[integrator]\nperiods = 100000\n[model]\ncontact = fast-grid\n";
    snprintf(path, sizeof path, "%s/long.ini", dir);
    bad_input_write_bytes(path, long_scene, strlen(long_scene));
    snprintf(path, sizeof path, "%s/long-summary.json", dir);
    mkdir(path, 0755);
    char *listing = bad_input_snapshot(dir);
    const double start = (double)clock() / CLOCKS_PER_SEC;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    code = run_here(dir, "run long.ini", out, sizeof out);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    (void)start;
    const double seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    char *listing_after = bad_input_snapshot(dir);
    gb_check cd = {"-", "-", "gomboc run with a directory where NAME-summary.json goes (a 10^5-period scene)",
                   "exit 2 naming the output before the run (under 5 s; the run takes minutes), the directory unchanged", "exact"};
    gb_check_true(&cd, code == 2 && strstr(out, "long-summary.json' exists and is not a regular file") && seconds < 5.0 &&
                       !strcmp(listing, listing_after), "exit %d after %.2f s: %.300s", code, seconds, out);
    free(listing), free(listing_after);
    rmdir(path);

    /* A link planted where an older version put its temporary (FILE.tmp) is never followed. */
    char victim[512];
    snprintf(victim, sizeof victim, "%s/victim.txt", dir);
    bad_input_write_bytes(victim, "not an atlas\n", 13);
    snprintf(path, sizeof path, "%s/shared.atlas.tmp", dir);
    if (symlink("victim.txt", path) != 0) path[0] = '\0';
    code = run_here(dir, "run a.ini --atlas shared.atlas", out, sizeof out);
    char *victim_text = gb_check_read_file(victim);
    gb_check cl = {"-", "-", "gomboc run --atlas F with a link F.tmp -> victim planted beside it", "exit 0, the victim unchanged",
                   "exact"};
    gb_check_true(&cl, path[0] && code == 0 && victim_text && !strcmp(victim_text, "not an atlas\n"), "exit %d: %.300s", code, out);
    free(victim_text);

    /* Two runs writing one atlas at once, 12 times: every run ends 0 with all its outputs; the atlas
     * is whole (a run that loads it says loaded). */
    int failures = 0;
    for (int trial = 0; trial < 12; trial++) {
        snprintf(path, sizeof path, "%s/race.atlas", dir);
        remove(path);
        char command[2 * 4096 + 1024]; /* the binary's path (up to 4096) twice, whole */
        snprintf(command, sizeof command,
                 "mkdir -p o1 o2 && { %s run a.ini --out o1 --atlas race.atlas & %s run a.ini --out o2 --atlas race.atlas & "
                 "wait %%1; e1=$?; wait %%2; e2=$?; test $e1 -eq 0 -a $e2 -eq 0 -a -f o1/a-summary.json -a -f o2/a-summary.json; }",
                 bad_input_binary(), bad_input_binary());
        failures += bad_input_run_in(dir, command, out, sizeof out) != 0;
    }
    code = run_here(dir, "run a.ini --atlas race.atlas --json", out, sizeof out);
    gb_check cr = {"-", "-", "two gomboc run writing one atlas file at once, 12 trials",
                   "every run exit 0 with its outputs; the atlas left is whole and loads", "exact"};
    gb_check_true(&cr, failures == 0 && code == 0 && strstr(out, "\"loaded\":\t1"), "%d of 12 trials failed; the reload: exit %d",
                  failures, code);

    /* An atlas file of 1 GiB (sparse: no disk) is larger than any atlas of the scene's levels: refused
     * unread, the atlas built anew and written back. Its memory is measured against the same run with no
     * atlas file at all (a sanitizer's shadow memory or a different allocator moves both alike): it may
     * exceed that by no more than the atlas limit, 64 MiB, where reading the file would take 1 GiB. */
    snprintf(path, sizeof path, "%s/huge.atlas", dir);
    FILE *huge = fopen(path, "wb"); /* an atlas file by its first bytes (a cache, to be replaced), but too large */
    const int made = huge && fwrite(GB_ATLAS_FILE_MAGIC, 1, sizeof GB_ATLAS_FILE_MAGIC, huge) == sizeof GB_ATLAS_FILE_MAGIC &&
                     fseek(huge, (1L << 30) - 1, SEEK_SET) == 0 && fputc(0, huge) != EOF;
    if (huge) fclose(huge);
    char summary_path[512];
    snprintf(summary_path, sizeof summary_path, "%s/a-summary.json", dir);
    long kib_of[2] = {0, 0};
    int code_of[2] = {-1, -1};
    static const char *const atlas_of[2] = {"fresh.atlas", "huge.atlas"};
    for (int run = 0; run < 2; run++) {
        remove(summary_path);
        const pid_t child = fork();
        if (child == 0) {
            bad_input_child_signals(0);
            if (chdir(dir) != 0 || !freopen("/dev/null", "w", stderr)) _exit(127);
            execl(bad_input_binary(), "gomboc", "run", "a.ini", "--atlas", atlas_of[run], (char *)NULL);
            _exit(127);
        }
        int wstatus = 0;
        struct rusage usage;
        memset(&usage, 0, sizeof usage);
        code_of[run] = wait4(child, &wstatus, 0, &usage) == child && WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : -1;
        kib_of[run] = usage.ru_maxrss; /* KiB on Linux */
    }
    code = code_of[1] ? code_of[1] : code_of[0];
    const long kib = kib_of[1];
    char *summary = gb_check_read_file(summary_path);
    snprintf(out, sizeof out, "%s", summary ? summary : "");
    free(summary);
    struct stat st;
    gb_check ca = {"-", "-", "gomboc run --atlas F, F a sparse file of 1 GiB that starts as an atlas file does", "exit 0, not loaded, the run's peak memory within "
                   "64 MiB (the atlas limit) of the same run with no atlas file, F replaced by the atlas built (under the "
                   "64 MiB limit)", "exact"};
    gb_check_true(&ca, made && code == 0 && strstr(out, "\"loaded\":\t0") && kib > 0 && kib_of[0] > 0 &&
                       kib < kib_of[0] + 64 * 1024 && stat(path, &st) == 0 && st.st_size < (64L << 20),
                  "exit %d, max resident %ld KiB (%ld KiB with no atlas file), file now %lld bytes", code, kib, kib_of[0],
                  stat(path, &st) == 0 ? (long long)st.st_size : -1LL);

    /* Output sets: the summary lists the others with size and checksum; a set mixed by a kill between
     * two renames (an older history beside the newer summary) and a stale output are found. */
    const char *set_scene = "[integrator]\nperiods = 2\nsteps_per_period = 40\n[model]\ncontact = fast-grid\n"
                            "[diagnostics]\nstrobe = yes\n[strobe]\ntransient_periods = 0\n";
    snprintf(path, sizeof path, "%s/set.ini", dir);
    bad_input_write_bytes(path, set_scene, strlen(set_scene));
    const int first = run_here(dir, "run set.ini", out, sizeof out);
    char older[512];
    snprintf(older, sizeof older, "%s/set-history.csv", dir);
    char *old_history = gb_check_read_file(older);
    const char *longer = "[integrator]\nperiods = 3\nsteps_per_period = 40\n[model]\ncontact = fast-grid\n"
                         "[diagnostics]\nstrobe = yes\n[strobe]\ntransient_periods = 0\n";
    bad_input_write_bytes(path, longer, strlen(longer));
    const int second = run_here(dir, "run set.ini", out, sizeof out);
    const int whole = run_here(dir, "check set-summary.json", out, sizeof out);
    char whole_text[512];
    snprintf(whole_text, sizeof whole_text, "%.500s", out);
    if (old_history) bad_input_write_bytes(older, old_history, strlen(old_history));
    const int mixed = run_here(dir, "check set-summary.json", out, sizeof out);
    const int named = strstr(out, "CHANGED set-history.csv") && strstr(out, "ok set-strobe.csv") && strstr(out, "MIXED");
    snprintf(path, sizeof path, "%s/set-spectrum.csv", dir);
    bad_input_write_bytes(path, "stale\n", 6);
    const int stale = run_here(dir, "check set-summary.json", out, sizeof out);
    gb_check cs = {"-", "-", "gomboc check on a run's summary: the set whole; an older history put back; a stale output added",
                   "exit 0; exit 1 naming the history; exit 1 naming the stale file", "exact"};
    gb_check_true(&cs, first == 0 && second == 0 && whole == 0 && mixed == 1 && named && stale == 1 &&
                       strstr(out, "NOT IN THE SET set-spectrum.csv"),
                  "runs %d %d; check: whole %d (%s), mixed %d (named %d), stale %d: %.300s", first, second, whole, whole_text,
                  mixed, named, stale, out);
    free(old_history);

    /* An error about a path of 3000 characters quotes it whole. */
    char deep[4096];
    deep_directory(dir, 2950, deep, sizeof deep);
    char args[4600];
    snprintf(args, sizeof args, "run '%s/missing-scene.ini'", deep);
    code = run_here(dir, args, out, sizeof out);
    char whole_path[4200];
    snprintf(whole_path, sizeof whole_path, "%s/missing-scene.ini: cannot open the case file", deep);
    gb_check cp = {"-", "-", "gomboc run of a missing scene at a path of about 3000 characters", "exit 2, the path quoted whole",
                   "exact"};
    gb_check_true(&cp, code == 2 && strstr(out, whole_path), "exit %d, %zu-character path, message of %zu characters", code,
                  strlen(deep) + 18, strlen(out));
    gb_check_tempdir_remove(dir);
}

/* cases/README.md states, for every key, the allowed values the reader enforces, in the same words. */
static void test_documented_ranges(void)
{
    FILE *f = fopen("cases/README.md", "r");
    static char text[1 << 17];
    const size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
    if (f) fclose(f);
    text[n] = '\0';
    size_t documented = 0;
    const size_t total = gb_case_key_count();
    char missing[2048] = "";
    for (size_t k = 0; k < total; k++) {
        const char *section, *name;
        char allowed[256], row[400];
        gb_case_key_allowed(k, &section, &name, allowed, sizeof allowed);
        snprintf(row, sizeof row, "| `[%s]` | `%s` | %s |", section, name, allowed);
        if (strstr(text, row)) documented++;
        else if (strlen(missing) < sizeof missing - 300) strcat(missing, row), strcat(missing, "\n");
    }
    gb_check c = {"-", "-", "cases/README.md has a row `| [section] | key | allowed |` for every key, as the reader enforces it",
                  "gb_case_key_allowed", "exact"};
    gb_check_true(&c, documented == total, "%zu of %zu keys documented; missing or different:\n%s", documented, total, missing);
}

int verify_register_bad_input(void)
{
    static const verify_test tests[] = {
        {"bad input: every row refused with exit status, key or option, range, and nothing written", test_bad_input_table, NULL},
        {"bad input: strict but fair (valid values accepted, long paths whole)", test_strict_but_fair, NULL},
        {"bad input: temporaries removed after SIGTERM and after a kill -9", test_temporaries, NULL},
        {"bad input: outputs never an input, checked before the run, written as sets, safe to race", test_outputs, NULL},
        {"bad input: the documented ranges are the enforced ranges", test_documented_ranges, NULL},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Bad input, never misread", tests);
}
