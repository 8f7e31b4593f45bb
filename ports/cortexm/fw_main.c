/*
 * The firmware simulation: the executive of src/ run from real interrupts.
 *
 *   SysTick (highest priority)  every 2 us: exec_fast_tick(), which at a
 *                               motor-frame boundary releases the medium
 *                               task by pending PendSV;
 *   PendSV (below SysTick)      exec_medium_tick(): the motor; every 8th
 *                               time it releases the controller task by
 *                               pending the board's software interrupt;
 *                               the fast tick preempts it;
 *   software IRQ (below PendSV) exec_control_tick(): the controller, whose
 *                               result the motor task takes a control
 *                               frame later; both preempt it;
 *   thread mode                 the background loop: exec_slow_step()
 *                               (battery, vessel) when a slow frame is due,
 *                               then the telemetry record over the UART;
 *                               in between it waits (see fw_background()).
 *
 * The run is described on the emulator's semihosting command line as
 * words key=value: scenario=FILE (read from the host through semihosting)
 * and optionally duration=SECONDS, e.g.
 *   -semihosting-config enable=on,target=native,arg=uuvsim,
 *                       arg=scenario=scenarios/default.scn,arg=duration=2
 * The telemetry stream (src/telemetry.h) goes to the UART; a summary goes
 * to the semihosting console. Exit status, as the desk simulator's: 0 the
 * run completed, 1 it stopped on an overrun, 2 bad input; a fault exits
 * with 3 (startup.c).
 *
 * The multi-party image (FW_PARTY=1, uuvsim_party.elf; docs/cosimulation.md)
 * runs the drive alone: at each slow boundary the background sends the
 * drive's measurements over the UART (a LINK_UP frame, src/telemetry.h)
 * to the host process that runs the slow segment, holds the fast tick's
 * timer, and waits for its answer (LINK_DOWN), which it checks and gives
 * the drive (exec_drive_take). A frame that fails a check ends the run
 * with a message naming it and exit status 2. The UART carries START,
 * the LINK_UP frames and END; no records.
 */
#include "armv7m.h"
#include "board.h"
#include "executive.h"
#include "fast_kernel.h"
#include "fw_params.h"
#include "hal/hal.h"
#include "hal_cortexm.h"
#include "scenario.h"
#include "telemetry.h"
#include "util/fmt.h"
#include "util/parse.h"
#include "uuv_config.h"

#define FW_CMDLINE_MAX 256u
#define FW_STACK_PAINT 0x5AC4A11Eu

extern uint32_t __stack_bottom__[], __stack_top__[];

/*
 * The scenario's text is needed only until it is parsed, and the
 * executive only from exec_init() on, so they share their RAM: on the
 * smallest machine that is a third of the budget.
 */
static union {
    exec e;
    char text[sizeof(exec)];
} fw_mem;

#define fw_exec (fw_mem.e)

static scenario fw_scn;
static exec_frame fw_report;
static uint8_t fw_frame[TLM_FRAME_MAX];
static uint16_t fw_seq;

/*
 * A test build (FW_OVERRUN_TEST=1) accepts overrun=fast|medium|slow on the
 * command line and then makes the first step of that rate run long, to
 * show that each level's overrun stops the run cleanly and is reported;
 * overrun=slowed makes every fast tick longer, to show that make test
 * fails an image that no longer keeps real time at its claimed shift.
 */
#ifndef FW_OVERRUN_TEST
#define FW_OVERRUN_TEST 0
#endif

#ifndef FW_PARTY
#define FW_PARTY 0
#endif

#if FW_OVERRUN_TEST
enum { FW_RATE_FAST, FW_RATE_MEDIUM, FW_RATE_SLOW, FW_RATES };
static const uint32_t fw_spin_count[FW_RATES] = {2000u, 100000u, 20000000u};
static bool fw_spin_armed[FW_RATES];

/* overrun=slowed: every fast tick some 350 instructions longer, not only the first. */
static bool fw_slowed;

static void fw_spin_once(int rate) {
    if (rate == FW_RATE_FAST && fw_slowed) {
        for (volatile uint32_t i = 0; i < 70u; i = i + 1u) {
        }
    }
    if (fw_spin_armed[rate]) {
        fw_spin_armed[rate] = false;
        for (volatile uint32_t i = 0; i < fw_spin_count[rate]; i = i + 1u) {
        }
    }
}
#define FW_SPIN(rate) fw_spin_once(rate)
#else
#define FW_SPIN(rate) ((void)0)
#endif

/* ---- Interrupt contexts -------------------------------------------------- */

/*
 * The fast tick: one fast step. The run is a whole number of motor
 * frames; the tick that releases the last motor task (one after the last
 * step) is the last, as the executive then says (exec_fast_ended()), and
 * the ticks stop (off the common path).
 */
static void fw_fast(void) {
    if (exec_fast_tick(&fw_exec)) {
        hal_medium_release();
        if (exec_fast_ended(&fw_exec)) {
            hal_cm_fast_stop();
        }
    }
    FW_SPIN(FW_RATE_FAST);
}

static void fw_medium(void) {
    if (exec_medium_tick(&fw_exec)) {
        hal_control_release();
    }
    FW_SPIN(FW_RATE_MEDIUM);
}

static void fw_control(void) { exec_control_tick(&fw_exec); }

/* ---- Telemetry ------------------------------------------------------------ */

static void fw_send(size_t n) {
    hal_telemetry_write(fw_frame, n);
    fw_seq++;
}

static void fw_send_start(const char *machine) {
    const exec *e = &fw_exec;
    tlm_start s = {TLM_VERSION, (uint8_t)UUV_NUMERIC, (uint8_t)e->cfg.plant, e->cfg.fast_ns,
                   e->cfg.fast_per_medium, e->cfg.medium_per_control, e->cfg.medium_per_slow,
                   e->frames, (double)e->frames * e->slow_s, {0}};
    for (size_t i = 0; i + 1u < TLM_MACHINE_CHARS && machine[i] != '\0'; i++) {
        s.machine[i] = machine[i];
    }
    fw_send(tlm_encode_start(fw_frame, fw_seq, &s));
}

static void fw_send_report(void) {
    if (!FW_PARTY && exec_report_take(&fw_exec, &fw_report)) {
        fw_send(tlm_encode_record(fw_frame, fw_seq, &fw_report));
    }
}

#if FW_PARTY
/* ---- The multi-party link ---------------------------------------------------- */

static tlm_link_up fw_up;
static tlm_link_down fw_down;
static uint8_t fw_rx[TLM_HEADER_BYTES + TLM_LINK_DOWN_PAYLOAD + TLM_CRC_BYTES];
static uint16_t fw_rx_seq; /* the sequence number the next frame from the host must carry */

/* A frame from the host failed a check: the run ends (exit status 2). */
static void fw_link_fail(const char *why) {
    fmt_print("uuvsim: link: frame %u from the host (the answer to slow frame %u): %s\n",
              (unsigned)fw_rx_seq, (unsigned)fw_up.frame, why);
    hal_exit(2);
}

/* Reads the host's answer to fw_up and checks it: framing, CRC, type, sequence, frame. */
static void fw_link_receive(void) {
    tlm_frame f;
    hal_cm_link_read(fw_rx, TLM_HEADER_BYTES);
    tlm_status st = tlm_frame_check(fw_rx, TLM_HEADER_BYTES, &f);
    if (st == TLM_TRUNCATED) {
        hal_cm_link_read(fw_rx + TLM_HEADER_BYTES, sizeof fw_rx - TLM_HEADER_BYTES);
        st = tlm_frame_check(fw_rx, sizeof fw_rx, &f);
    }
    if (st != TLM_OK) {
        fw_link_fail(st == TLM_TRUNCATED ? "not a LINK_DOWN frame" : tlm_status_text(st));
    }
    if (f.type != (uint8_t)TLM_LINK_DOWN) {
        fw_link_fail("not a LINK_DOWN frame");
    }
    if (f.seq != fw_rx_seq) {
        fw_link_fail("out of sequence (a frame was lost)");
    }
    tlm_decode_link_down(&f, &fw_down);
    if (fw_down.frame != fw_up.frame) {
        fw_link_fail("answers another slow frame");
    }
    fw_rx_seq++;
}

/*
 * The slow step, by the link: the measurements of the slow frame that
 * ended go to the host, and its results come back, the fast tick held in
 * between (lock-step).
 */
static void fw_party_step(void) {
    hal_cm_fast_hold(true);
    fw_up.frame++;
    drive_slow_measure(&fw_exec.drive, &fw_up.meas);
    fw_up.speed_rpm = fw_exec.speed_report_rpm;
    fw_send(tlm_encode_link_up(fw_frame, fw_seq, &fw_up));
    fw_link_receive();
    exec_drive_take(&fw_exec, &fw_down.down);
    hal_cm_fast_hold(false);
}
#endif

/*
 * One unit of background work: the slow step and its telemetry record.
 * Kept out of line, and its calls kept calls by the empty barrier at the
 * end, so that the instruction counts find where it begins and returns.
 */
void fw_background_step(void);

__attribute__((noinline)) void fw_background_step(void) {
    FW_SPIN(FW_RATE_SLOW);
#if FW_PARTY
    fw_party_step();
#else
    exec_slow_step(&fw_exec);
    fw_send_report();
#endif
    __asm__ volatile("" ::: "memory");
}

/* ---- Stack high-water mark -------------------------------------------------- */

/* Fills the unused stack below the current frame (with a margin) with a pattern. */
static void stack_paint(void) {
    uint32_t *p = __stack_bottom__;
    uint32_t *limit = (uint32_t *)(cpu_sp() - 64u);
    while (p < limit) {
        *p++ = FW_STACK_PAINT;
    }
}

/* Bytes of stack ever used: from the top down to the lowest overwritten word. */
static uint32_t stack_used(void) {
    const uint32_t *p = __stack_bottom__;
    while (p < __stack_top__ && *p == FW_STACK_PAINT) {
        p++;
    }
    return (uint32_t)((uintptr_t)__stack_top__ - (uintptr_t)p);
}

/* ---- The run's description ------------------------------------------------ */

typedef struct {
    char line[FW_CMDLINE_MAX];
    const char *scenario_path; /* inside line */
    double duration_s;         /* 0: the scenario's */
} fw_args;

static bool fw_fail(const char *what, const char *detail) {
    fmt_print("uuvsim: %s%s\n", what, detail);
    return false;
}

static bool fw_key_is(const char *tok, size_t n, const char *key, size_t *value_at) {
    size_t k = 0;
    while (key[k] != '\0' && k < n && tok[k] == key[k]) {
        k++;
    }
    if (key[k] != '\0' || k >= n || tok[k] != '=') {
        return false;
    }
    *value_at = k + 1u;
    return true;
}

/*
 * The start-up steps are kept out of line: their locals then live only
 * while they run, not in main's frame for the whole run.
 */

/* Reads scenario=FILE and duration=S from the command line (words split in place). */
__attribute__((noinline)) static bool fw_parse_args(fw_args *a) {
    *a = (fw_args){{0}, NULL, 0.0};
    int32_t len = hal_cm_cmdline(a->line, sizeof a->line);
    if (len < 0) {
        return fw_fail("no semihosting command line", " (expected scenario=FILE [duration=S])");
    }
    parse_token tok[8];
    size_t n = parse_tokens(a->line, (size_t)len, tok, 7u);
    if (n > 7u) {
        return fw_fail("too many words on the command line", "");
    }
    for (size_t i = 0; i < n; i++) {
        char *t = a->line + (tok[i].text - a->line);
        size_t at = 0;
        t[tok[i].len] = '\0';
        if (fw_key_is(t, tok[i].len, "scenario", &at) && at < tok[i].len) {
            a->scenario_path = t + at;
        } else if (fw_key_is(t, tok[i].len, "duration", &at)) {
            size_t used = 0;
            size_t vn = tok[i].len - at;
            if (!parse_number(t + at, vn, &a->duration_s, &used) || used != vn ||
                !(a->duration_s > 0.0 && a->duration_s <= 1e6)) {
                return fw_fail("duration: expected seconds in (0, 1e6], got ", t + at);
            }
#if FW_OVERRUN_TEST
        } else if (fw_key_is(t, tok[i].len, "overrun", &at)) {
            static const char *const rates[FW_RATES] = {"fast", "medium", "slow"};
            for (int r = 0; r < FW_RATES; r++) {
                fw_spin_armed[r] = parse_word_is(t + at, tok[i].len - at, rates[r]);
            }
            fw_slowed = parse_word_is(t + at, tok[i].len - at, "slowed");
#endif
        } else if (i > 0u) {
            return fw_fail("unknown word on the command line: ", t);
        }
    }
    if (a->scenario_path == NULL) {
        return fw_fail("no scenario", " (expected scenario=FILE on the command line)");
    }
    return true;
}

/* Reads the scenario file through semihosting and parses it. */
__attribute__((noinline)) static bool fw_load_scenario(const char *path) {
    if (!hal_cm_input_open(path)) {
        return fw_fail(path, ": cannot open (through semihosting)");
    }
    size_t n = 0;
    for (;;) {
        size_t got = hal_input_read((uint8_t *)fw_mem.text + n, sizeof fw_mem.text - n);
        n += got;
        if (got == 0u || n == sizeof fw_mem.text) {
            break;
        }
    }
    uint8_t extra;
    bool too_long = (n == sizeof fw_mem.text) && hal_input_read(&extra, 1u) > 0u;
    hal_cm_input_close();
    if (too_long) {
        fmt_print("uuvsim: %s: longer than %u bytes\n", path, (unsigned)sizeof fw_mem.text);
        return false;
    }
    scenario_error err;
    if (!scenario_parse(&fw_scn, fw_mem.text, n, &err)) {
        fmt_print("uuvsim: %s:%u: %s%s%s%s\n", path, err.line, err.field[0] ? "field '" : "",
                  err.field, err.field[0] ? "': " : "", err.message);
        return false;
    }
    return true;
}

/* Checks the run and initialises the executive; the first record is then ready. */
__attribute__((noinline)) static bool fw_init(const fw_args *a, const char *path) {
    exec_config cfg;
    exec_config_default(&cfg);
    cfg.params = fw_params;
    cfg.duration_s = a->duration_s;
    if (cfg.duration_s <= 0.0 && fw_scn.duration_s <= 0.0) {
        return fw_fail(path, ": no duration (give 'duration <s>' or duration=S)");
    }
    exec_status st = exec_init(&fw_exec, &cfg, &fw_scn);
    if (st != EXEC_OK) {
        return fw_fail(st != EXEC_ERR_MODEL ? "the frames, duration or options are out of range"
                                            : "a model refused its parameters at these frames",
                       "");
    }
#if FW_FAST_KERNEL
    drive_use_fast_kernel(&fw_exec.drive, drive_fast_kernel_v7m);
#endif
    const exec_config *c = &fw_exec.cfg;
    uint64_t steps = (uint64_t)fw_exec.frames * c->medium_per_slow * c->fast_per_medium;
    if (steps > 0xFFFFFFFFu) {
        return fw_fail("the run is longer than 2^32 fast steps", " (shorten the duration)");
    }
    return true;
}

/* ---- The run ----------------------------------------------------------------- */

/*
 * The background loop. By default it polls, with interrupts enabled: the
 * flags it reads are single loads, and a stale one only costs another
 * turn of the loop, so the fast tick never waits for it. With FW_IDLE_WFI
 * it sleeps between interrupts, as a board would to save power: the last
 * test and the sleep happen with interrupts masked, and an interrupt that
 * arrives in between still ends the WFI (a pending interrupt wakes the
 * core whatever PRIMASK says), so no wake-up is lost; the masked test
 * delays a tick by a few instructions. Under QEMU's -icount every wake-up
 * from WFI costs the emulator a hand-off between its threads, which makes
 * a run some 50 times slower, while polling costs only instructions, and
 * those are what virtual time is made of. The results are the same either
 * way.
 */
#ifndef FW_IDLE_WFI
#define FW_IDLE_WFI 0
#endif

static bool fw_stopping(void) {
    return fw_exec.state != EXEC_RUNNING || hal_cm_fast_overruns() != 0u;
}

static void fw_background(void) {
    while (!fw_stopping()) {
        if (exec_slow_pending(&fw_exec)) {
            fw_background_step();
        } else if (FW_IDLE_WFI) {
            hal_critical_enter();
            if (!fw_stopping() && !exec_slow_pending(&fw_exec)) {
                hal_wait_for_tick();
            }
            hal_critical_exit();
        }
    }
}

__attribute__((noinline)) static int fw_finish(void) {
    const exec *e = &fw_exec;
    uint32_t of = hal_cm_fast_overruns();
    bool done = e->state == EXEC_DONE && of == 0u;
    bool nonfinite = e->state == EXEC_STOP_NONFINITE && of == 0u;
    int status = done ? 0 : (nonfinite ? 3 : 1);
    tlm_end end = {(uint8_t)e->state, (uint8_t)status, exec_fast_steps(e), e->count.medium,
                   e->count.control, e->count.slow, of, e->count.overruns_medium,
                   e->count.overruns_control, e->count.overruns_slow, e->count.saturations, e->count.e_batt_j,
                   e->count.e_mech_j, stack_used()};
    fw_send(tlm_encode_end(fw_frame, fw_seq, &end));
    fmt_print("uuvsim firmware on %s, %s build: %.1f s simulated, %s\n", board_name,
              UUV_NUMERIC_NAME, exec_time_s(e), done ? "completed" : "stopped early");
    fmt_print("steps: %llu fast, %llu motor, %llu control, %llu slow; overruns: %u fast, "
              "%u motor, %u control, %u slow; %u saturations\n",
              (unsigned long long)exec_fast_steps(e), (unsigned long long)e->count.medium,
              (unsigned long long)e->count.control, (unsigned long long)e->count.slow,
              (unsigned)of, (unsigned)e->count.overruns_medium,
              (unsigned)e->count.overruns_control, (unsigned)e->count.overruns_slow,
              (unsigned)e->count.saturations);
    fmt_print("stack: %u of %u bytes used\n", (unsigned)end.stack_used_bytes,
              (unsigned)((uintptr_t)__stack_top__ - (uintptr_t)__stack_bottom__));
    if (nonfinite) {
        fmt_print("stopped early: a state became non-finite or diverged\n");
    } else if (!done) {
        fmt_print("stopped early: a %s overran its frame\n",
                  of != 0u                            ? "fast tick"
                  : e->count.overruns_medium != 0u    ? "motor task"
                  : e->count.overruns_control != 0u   ? "controller task"
                                                      : "slow step");
    }
    return status;
}

int main(void) {
    stack_paint();
    static fw_args args;
    if (!fw_parse_args(&args) || !fw_load_scenario(args.scenario_path) ||
        !fw_init(&args, args.scenario_path)) {
        hal_exit(2);
    }
    fw_send_start(board_name);
    fw_send_report();
    hal_ticks_config ticks = {fw_exec.cfg.fast_ns, fw_fast, fw_medium, fw_control};
    hal_cm_stop_on_overrun(true);
    if (!hal_ticks_start(&ticks)) {
        (void)fw_fail("the fast frame is out of the timer's range", "");
        hal_exit(2);
    }
    fw_background();
    hal_ticks_stop();
    hal_exit(fw_finish());
}
