/* Bad input that needs a second process, a lock, a signal or a file-size limit: what the command does when its
 * parent ignores a signal, when another process holds its lock or left a temporary behind, when the disk fills,
 * when two runs write one name at once, and the rest of round 3 (a foreign key's cache, an axis the base refuses,
 * a FIFO beside the outputs, coarse steps, coincident impact points). The table of single bad inputs and its
 * runner are bad_input.c's (bad_input.h). */
#include "bad_input.h"
#include "gb_check.h"
#include "verify_sections.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

/* ---- round 3: what needs a second process, a lock, a signal or a file-size limit --------------------- */

/* A scene that runs for minutes, its history's temporary appearing at once. */
static const char *const long_scene = "[integrator]\nperiods = 100000\n[model]\ncontact = fast-grid\n";

/* Start `gomboc run CASE --out DIR` with signal `ignored` ignored (0: none) and wait until its first
 * temporary appears in `dir` (up to 10 s): the child's pid, or -1. */
static pid_t start_run(const char *dir, const char *case_path, int ignored)
{
    const pid_t child = fork();
    if (child == 0) {
        bad_input_child_signals(ignored); /* as nohup, or a shell's background job, leaves it */
        if (!freopen("/dev/null", "w", stderr)) _exit(127);
        execl(bad_input_binary(), "gomboc", "run", case_path, "--out", dir, (char *)NULL);
        _exit(127);
    }
    for (int k = 0; k < 200 && child > 0 && bad_input_count_temporaries(dir) == 0; k++) usleep(50000);
    return child;
}

/* (3) A signal the parent ignored stays ignored: SIGHUP under nohup, SIGINT for a background job. */
static void test_signals_ignored(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("sig", dir, sizeof dir)) return;
    char case_path[320];
    snprintf(case_path, sizeof case_path, "%s/long.ini", dir);
    bad_input_write_bytes(case_path, long_scene, strlen(long_scene));
    static const int signals[] = {SIGHUP, SIGINT};
    char report[512] = "";
    int kept = 0;
    for (int k = 0; k < 2; k++) {
        const pid_t child = start_run(dir, case_path, signals[k]);
        const int started = bad_input_count_temporaries(dir) > 0;
        kill(child, signals[k]);
        usleep(300000);
        int wstatus = 0;
        const int alive = waitpid(child, &wstatus, WNOHANG) == 0;
        kill(child, SIGTERM); /* still ours to end */
        if (alive) waitpid(child, &wstatus, 0);
        const int ok = started && alive && WIFSIGNALED(wstatus) && WTERMSIG(wstatus) == SIGTERM && bad_input_count_temporaries(dir) == 0;
        kept += ok;
        snprintf(report + strlen(report), sizeof report - strlen(report), "%s%s: started %d, alive after it %d, ended by "
                 "SIGTERM %d, temporaries left %d", k ? "; " : "", strsignal(signals[k]), started, alive,
                 WIFSIGNALED(wstatus) && WTERMSIG(wstatus) == SIGTERM, bad_input_count_temporaries(dir));
    }
    gb_check c = {"-", "-", "gomboc run with SIGHUP ignored by its parent (nohup), then with SIGINT ignored (a background job)",
                  "the signal changes nothing; SIGTERM still ends the run and removes its temporaries", "exact"};
    gb_check_true(&c, kept == 2, "%s", report);
    gb_check_tempdir_remove(dir);
}

/* (4) A lock held by another process is waited for a bounded time, then named; the run says so before its
 * computation. */
static void test_lock_bounded(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("lock", dir, sizeof dir)) return;
    char path[256], out[4096], command[1024];
    snprintf(path, sizeof path, "%s/a.ini", dir);
    const char *atlas_scene = "[model]\nequation = rolling\ncontact = continuous\ncertificate = atlas\n[integrator]\nperiods = 1\n";
    bad_input_write_bytes(path, atlas_scene, strlen(atlas_scene));
    const int held = open(dir, O_RDONLY | O_DIRECTORY);
    const int locked = held >= 0 && flock(held, LOCK_EX) == 0; /* as a writer stopped with Ctrl-Z while merging holds it */
    char *before = bad_input_snapshot(dir);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    snprintf(command, sizeof command, "env GOMBOC_LOCK_SECONDS=1 %s run a.ini --atlas shared.atlas", bad_input_binary());
    const int code = bad_input_run_in(dir, command, out, sizeof out);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    char *after = bad_input_snapshot(dir);
    const double seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    if (held >= 0) close(held); /* the lock goes with it */
    snprintf(command, sizeof command, "env GOMBOC_LOCK_SECONDS=1 %s run a.ini --atlas shared.atlas", bad_input_binary());
    const int freed = bad_input_run_in(dir, command, out + 2048, sizeof out - 2048);
    gb_check c = {"-", "-", "gomboc run --atlas F while another process holds the lock of F's directory (GOMBOC_LOCK_SECONDS=1)",
                  "exit 1 within a few seconds, naming the directory and the wait, nothing written; exit 0 once it is free",
                  "exact; the bound: 1 s of wait, 10 s in all for the start of the process"};
    gb_check_true(&c, locked && code == 1 && seconds < 10.0 && strstr(out, "stayed locked for 1 s") && strstr(out, dir) &&
                       before && after && !strcmp(before, after) && freed == 0,
                  "exit %d after %.2f s (then %d once free): %.300s", code, seconds, freed, out);
    free(before), free(after);
    gb_check_tempdir_remove(dir);
}

/* (5) A temporary whose writer lives where its PID cannot be seen (another PID namespace, another host on
 * NFS): its lock says it is alive, and it is left; once the lock goes, the next run removes it. */
static void test_foreign_temporary(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("ns", dir, sizeof dir)) return;
    char case_path[320], temp[320], command[512], out[4096];
    snprintf(case_path, sizeof case_path, "%s/quick.ini", dir);
    const char *quick = "[integrator]\nperiods = 1\nsteps_per_period = 20\n[model]\ncontact = fast-grid\n";
    bad_input_write_bytes(case_path, quick, strlen(quick));
    /* a PID that names no process here: the writer is in another namespace, alive */
    snprintf(temp, sizeof temp, "%s/.gomboc-%d-Ab3dEf", dir, 4194302);
    bad_input_write_bytes(temp, "half", 4);
    const int fd = open(temp, O_RDONLY);
    const int locked = fd >= 0 && flock(fd, LOCK_EX) == 0;
    snprintf(command, sizeof command, "%s run '%s' --out '%s'", bad_input_binary(), case_path, dir);
    const int live = bad_input_run_in(dir, command, out, sizeof out);
    const int kept = access(temp, F_OK) == 0;
    if (fd >= 0) close(fd);
    const int gone = bad_input_run_in(dir, command, out, sizeof out);
    const int removed = access(temp, F_OK) != 0;
    gb_check c = {"-", "-", "a temporary '.gomboc-PID-XXXXXX' of a PID that names no process here, its lock held (a live writer "
                  "in another PID namespace or on another host)", "left while locked; removed by the next run once its lock "
                  "is free", "exact"};
    gb_check_true(&c, locked && live == 0 && kept && gone == 0 && removed, "locked %d; run exit %d, temporary %s; after its "
                  "lock went: run exit %d, temporary %s", locked, live, kept ? "kept" : "REMOVED", gone,
                  removed ? "removed" : "LEFT");
    gb_check_tempdir_remove(dir);
}

/* (8, 14) Files limited to 4 KiB (ulimit -f, RLIMIT_FSIZE): the write fails with EFBIG, which the run
 * reports as any failed write (exit 1, naming the file), with no temporary left and nothing written. */
static void test_file_size_limit(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("fsize", dir, sizeof dir)) return;
    char case_path[320], log[320];
    snprintf(case_path, sizeof case_path, "%s/l.ini", dir);
    snprintf(log, sizeof log, "%s/../%s.log", dir, strrchr(dir, '/') + 1);
    const char *scene = "[model]\ncontact = fast-grid\n[integrator]\nperiods = 20\n[diagnostics]\nlyapunov = yes\n";
    bad_input_write_bytes(case_path, scene, strlen(scene));
    char *before = bad_input_snapshot(dir);
    const pid_t child = fork();
    if (child == 0) {
        bad_input_child_signals(0);
        const struct rlimit limit = {4096, 4096};
        if (setrlimit(RLIMIT_FSIZE, &limit) || !freopen(log, "w", stderr)) _exit(127);
        execl(bad_input_binary(), "gomboc", "run", case_path, "--out", dir, (char *)NULL);
        _exit(127);
    }
    int wstatus = 0;
    waitpid(child, &wstatus, 0);
    char *after = bad_input_snapshot(dir), *message = gb_check_read_file(log);
    remove(log);
    gb_check c = {"-", "-", "gomboc run of a scene with lambda, files limited to 4 KiB (ulimit -f)",
                  "exit 1 (not killed by SIGXFSZ), naming the history and 'File too large', not the Lyapunov pair; no "
                  "temporary left, the directory unchanged", "exact"};
    gb_check_true(&c, WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 1 && message && strstr(message, "l-history.csv") &&
                       strstr(message, "File too large") && !strstr(message, "sampler") && bad_input_count_temporaries(dir) == 0 &&
                       before && after && !strcmp(before, after),
                  "%s %d, temporaries %d, directory %s: %.300s", WIFEXITED(wstatus) ? "exit" : "signal",
                  WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : WTERMSIG(wstatus), bad_input_count_temporaries(dir),
                  before && after && !strcmp(before, after) ? "unchanged" : "CHANGED", message ? message : "(none)");
    free(before), free(after), free(message);
    gb_check_tempdir_remove(dir);
}

/* (18) Two runs of one scene name, from two directories, into one output directory at once: each set is
 * renamed into place with the directory locked, so the outputs are one whole set, whichever came last. */
static void test_concurrent_runs(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("race", dir, sizeof dir)) return;
    char path[256], out[8192], command[2048];
    static const char *const scenes[2] = {
        "[integrator]\nperiods = 2\nsteps_per_period = 40\n[model]\ncontact = fast-grid\n[diagnostics]\nstrobe = yes\n"
        "spectrum = yes\n[strobe]\ntransient_periods = 0\n[spectrum]\ntransient_periods = 0\n",
        "[integrator]\nperiods = 3\nsteps_per_period = 40\n[model]\ncontact = fast-grid\n[diagnostics]\nstrobe = yes\n"
        "spectrum = yes\n[strobe]\ntransient_periods = 0\n[spectrum]\ntransient_periods = 0\n"};
    for (int k = 0; k < 2; k++) {
        snprintf(path, sizeof path, "%s/%c", dir, 'a' + k);
        mkdir(path, 0755);
        snprintf(path, sizeof path, "%s/%c/s.ini", dir, 'a' + k);
        bad_input_write_bytes(path, scenes[k], strlen(scenes[k]));
    }
    snprintf(path, sizeof path, "%s/o", dir);
    mkdir(path, 0755);
    int whole = 0;
    const int trials = 12;
    for (int trial = 0; trial < trials; trial++) {
        snprintf(command, sizeof command, "sh -c '%s run a/s.ini --out o 2>/dev/null & %s run b/s.ini --out o 2>/dev/null & "
                 "wait %%1 && wait %%2 && %s check o/s-summary.json'", bad_input_binary(), bad_input_binary(), bad_input_binary());
        whole += bad_input_run_in(dir, command, out, sizeof out) == 0;
    }
    gb_check c = {"-", "-", "two runs of one scene name (2 and 3 periods, history, strobe, spectrum) into one directory at once, "
                  "12 trials", "both exit 0 and gomboc check finds the set whole, every trial", "exact"};
    gb_check_true(&c, whole == trials, "%d of %d trials whole: %.300s", whole, trials, out);
    gb_check_tempdir_remove(dir);
}

/* The rest: a cache sealed under another key, an axis the base refuses, a FIFO beside a run's outputs, a
 * step too coarse for the spin, and (6) the impact of two points 1e-15 apart. */
static void test_round3_runs(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("r3", dir, sizeof dir)) return;
    char path[256], out[8192], command[2048];
    /* (7) a hull sealed under another user's key is rebuilt, as a damaged one is */
    snprintf(path, sizeof path, "%s/h.ini", dir);
    const char *hull_scene = "[model]\ncontact = fast-grid\n[integrator]\nperiods = 1\nsteps_per_period = 20\n";
    bad_input_write_bytes(path, hull_scene, strlen(hull_scene));
    snprintf(command, sizeof command, "%s run h.ini --hull h.hull --json | grep -A2 '\"hull\"' && env GOMBOC_KEY=%s/other.key "
             "%s run h.ini --hull h.hull --json | grep -A2 '\"hull\"'", bad_input_binary(), dir, bad_input_binary());
    const int code = bad_input_run_in(dir, command, out, sizeof out);
    const char *second = strstr(out, "\"loaded\"") ? strstr(strstr(out, "\"loaded\"") + 1, "\"loaded\"") : NULL;
    gb_check ck = {"-", "-", "gomboc run --hull F, F sealed under another key (GOMBOC_KEY of another user)",
                   "not loaded (its seal does not verify), built anew and written back", "exact"};
    gb_check_true(&ck, code == 0 && second && strstr(second, "\"loaded\":\t0"), "exit %d: %.300s", code, out);

    /* (16) a scan axis whose value the base refuses is named by the scan file's line, not the base's default */
    snprintf(path, sizeof path, "%s/b.ini", dir);
    bad_input_write_bytes(path, "[integrator]\nperiods = 5\n", 25);
    snprintf(path, sizeof path, "%s/s.ini", dir);
    const char *scan = "[scan]\nbase = b.ini\nperiods = 5\ntransient_periods = 1\n[x]\nkey = model.restitution\nfrom = 0\n"
                       "to = 0.5\ncount = 2\n[y]\nkey = forcing.A1\nfrom = 1\nto = 2\ncount = 2\n";
    bad_input_write_bytes(path, scan, strlen(scan));
    char *before = bad_input_snapshot(dir);
    snprintf(command, sizeof command, "%s scan s.ini", bad_input_binary());
    const int axis = bad_input_run_in(dir, command, out, sizeof out);
    char *after = bad_input_snapshot(dir);
    gb_check ca = {"-", "-", "gomboc scan with [x] key = model.restitution over a base of the held law",
                   "exit 2 naming the scan file's [x] line and the point, the base as the scene, nothing written", "exact"};
    gb_check_true(&ca, axis == 2 && strstr(out, "s.ini:6 (point 1): [model] restitution") && strstr(out, "(in the scene b.ini)") &&
                       !strstr(out, "(default)") && before && after && !strcmp(before, after),
                  "exit %d: %.300s", axis, out);
    free(before), free(after);

    /* (2) a scan's shared atlas named by [scan] atlas_file over another scan's finished CSV */
    snprintf(path, sizeof path, "%s/other-scan.csv", dir);
    bad_input_write_bytes(path, "index,x,y\n0,1,2\n", 16);
    snprintf(path, sizeof path, "%s/rolling.ini", dir);
    bad_input_write_bytes(path, "[model]\nequation = rolling\ncontact = continuous\n", 48);
    snprintf(path, sizeof path, "%s/shared.ini", dir);
    const char *shared = "[scan]\nbase = rolling.ini\nperiods = 5\ntransient_periods = 1\natlas = shared\n"
                         "atlas_file = other-scan.csv\n[x]\nkey = forcing.omega\nfrom = 17\nto = 19\ncount = 2\n[y]\n"
                         "key = forcing.A1\nfrom = 1\nto = 2\ncount = 2\n";
    bad_input_write_bytes(path, shared, strlen(shared));
    before = bad_input_snapshot(dir);
    snprintf(command, sizeof command, "%s scan shared.ini", bad_input_binary());
    const int foreign = bad_input_run_in(dir, command, out, sizeof out);
    after = bad_input_snapshot(dir);
    gb_check cs = {"-", "-", "gomboc scan with [scan] atlas_file = other-scan.csv, another scan's finished CSV",
                   "exit 2 naming atlas_file and the file, which is left as it was; nothing written", "exact"};
    gb_check_true(&cs, foreign == 2 && strstr(out, "shared.ini:6: [scan] atlas_file './other-scan.csv' exists and is not an atlas file") &&
                       before && after && !strcmp(before, after),
                  "exit %d: %.300s", foreign, out);
    free(before), free(after);

    /* (19) a FIFO named like an output the run does not write is no output of its set */
    snprintf(path, sizeof path, "%s/h-lyapunov.csv", dir);
    mkfifo(path, 0644);
    snprintf(command, sizeof command, "%s run h.ini && %s check h-summary.json", bad_input_binary(), bad_input_binary());
    const int fifo = bad_input_run_in(dir, command, out, sizeof out);
    gb_check cf = {"-", "-", "gomboc check of a run's set beside a FIFO named NAME-lyapunov.csv (the run leaves it alone)",
                   "exit 0: the set is whole", "exact"};
    gb_check_true(&cf, fifo == 0 && strstr(out, "the set is whole"), "exit %d: %.300s", fifo, out);
    remove(path);

    /* (6) a drop at 4 km/s that meets the plane with two points 9e-16 m apart: one point, no pull; and every
     * step turns the body by radians: warned, counted, the ledger's drift stated */
    snprintf(path, sizeof path, "%s/drop.ini", dir);
    const char *drop = "[model]\ncontact = continuous\nequation = rolling\ncontact_law = unilateral\n[integrator]\n"
                       "locate_switches = yes\nperiods = 2\n[initial]\nheight = 0.04067970569418181\n"
                       "velocity = 2482.079522183096,-2908.913684460292,-1537.2646754640605\n"
                       "omega = 16.481121288668746,-44.288031336110755,-12.051011432581646\n"
                       "attitude = axis-angle -0.20014281332391626,0.7600603375468236,0.5171210564083513,0.47204654708929905\n"
                       "[output]\nimpacts = yes\nhistory = no\n";
    bad_input_write_bytes(path, drop, strlen(drop));
    snprintf(command, sizeof command, "%s run drop.ini --json", bad_input_binary());
    const int dropped = bad_input_run_in(dir, command, out, sizeof out);
    snprintf(path, sizeof path, "%s/drop-impacts.csv", dir);
    char *impacts = gb_check_read_file(path);
    double worst = 0.0, scale = 0.0;
    int rows = 0;
    for (char *line = impacts ? strchr(impacts, '\n') : NULL; line && line[1]; line = strchr(line + 1, '\n')) {
        double field[30];
        int n = 0;
        for (char *p = line + 1; n < 30 && p && *p != '\n'; n++) {
            field[n] = strtod(p, NULL);
            p = strchr(p, ',');
            if (p) p++;
        }
        if (n < 27) continue;
        rows++;
        worst = fmin(worst, fmin(field[23], field[26])); /* normal_impulse, old_normal_impulse */
        scale = fmax(scale, fabs(field[23]));
    }
    free(impacts);
    gb_check cd = {"-", "-", "a unilateral drop at 4 km/s spinning at 50 rad/s whose impact meets two points 9e-16 m apart "
                   "(one point: GB_IMPACT_SAME_POINT = 1e-9 of the body)", "exit 0; no normal impulse below -1e-9 of the "
                   "largest (a pull of 5.5e18 N s before); the summary counts the steps too coarse and the run warns with the "
                   "ledger's drift", "exact; the pull's bound is rounding, 1e-9 of the impulses"};
    gb_check_true(&cd, dropped == 0 && rows >= 2 && worst >= -1e-9 * scale && strstr(out, "\"steps_too_coarse\":\t320") &&
                       strstr(out, "the step is too coarse for the body's spin") && strstr(out, "energy ledger drifted"),
                  "exit %d, %d impacts, the most negative normal impulse %.3g of %.3g: %.200s", dropped, rows, worst, scale,
                  strstr(out, "warning") ? strstr(out, "warning") : out);
    gb_check_tempdir_remove(dir);
}


int verify_register_bad_input_processes(void)
{
    static const verify_test tests[] = {
        {"bad input: signals a parent ignored stay ignored", test_signals_ignored, NULL},
        {"bad input: a lock held elsewhere is waited for a bounded time, then named", test_lock_bounded, NULL},
        {"bad input: a temporary is removed only when its writer's lock is free, whatever its PID", test_foreign_temporary, NULL},
        {"bad input: a file-size limit is a failed write, not a kill", test_file_size_limit, NULL},
        {"bad input: two runs of one name into one directory leave one whole set", test_concurrent_runs, NULL},
        {"bad input: foreign caches, axes the base refuses, FIFOs, coarse steps and coincident impact points", test_round3_runs, NULL},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Bad input: signals, locks, races and full disks", tests);
}
