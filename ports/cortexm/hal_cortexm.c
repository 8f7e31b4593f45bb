/*
 * The HAL on ARMv7-M (Cortex-M3/M4/M7) under QEMU or on a board:
 *   - fast tick: SysTick, the highest priority;
 *   - medium tick: PendSV, below SysTick, pended by the fast tick, so the
 *     fast tick preempts it;
 *   - control tick: the board's software interrupt line (board_soft_irq),
 *     below PendSV, pended by the medium tick, preempted by both;
 *   - background: thread mode, sleeping in WFI between ticks;
 *   - console: semihosting (buffered per line); telemetry: the board's
 *     first UART; scenario input: a host file through semihosting;
 *   - exit: semihosting SYS_EXIT_EXTENDED, which carries the status.
 * A fast tick that is pending again when its handler ends has overrun: it
 * is counted, and SysTick stops if the program asked for it (see
 * hal_cortexm.h).
 */
#include "hal_cortexm.h"

#include "armv7m.h"
#include "board.h"
#include "hal/hal.h"
#include "semihost.h"

/* Priorities (upper bits significant on every core): fast > medium > control. */
#define PRIO_FAST 0x00u
#define PRIO_MEDIUM 0x80u
#define PRIO_CONTROL 0xC0u

static struct {
    bool initialised;
    int32_t console;   /* semihosting handle of ":tt", or -1 */
    int32_t input;     /* semihosting handle of the scenario input, or -1 */
    size_t line_len;
    hal_ticks_config ticks;
    uint32_t critical_depth;
    uint32_t critical_saved;
    volatile uint32_t fast_overruns;
    bool stop_on_overrun;
} hal_cm = {false, -1, -1, 0u, {0u, NULL, NULL, NULL}, 0u, 0u, 0u, false};

/* SysTick's control while held (hal_cm_fast_hold; only the multi-party image links it). */
static uint32_t hal_cm_held_csr;

/* The console buffer, flushed per line (apart: zero-initialised, it takes no flash). */
static char hal_cm_line[128];

static void hal_cm_init(void) {
    if (!hal_cm.initialised) {
        hal_cm.initialised = true;
        board_init();
        hal_cm.console = semihost_open(":tt", 4u);
    }
}

static void console_flush(void) {
    if (hal_cm.line_len > 0u && hal_cm.console >= 0) {
        (void)semihost_write(hal_cm.console, hal_cm_line, hal_cm.line_len);
    }
    hal_cm.line_len = 0u;
}

void hal_console_write(const char *text, size_t n) {
    hal_cm_init();
    for (size_t i = 0; i < n; i++) {
        hal_cm_line[hal_cm.line_len++] = text[i];
        if (text[i] == '\n' || hal_cm.line_len == sizeof hal_cm_line) {
            console_flush();
        }
    }
}

void hal_telemetry_write(const uint8_t *data, size_t n) {
    hal_cm_init();
    board_uart_write(data, n);
}

size_t hal_input_read(uint8_t *buf, size_t n) {
    if (hal_cm.input < 0 || n == 0u) {
        return 0u;
    }
    return semihost_read(hal_cm.input, buf, n);
}

bool hal_cm_input_open(const char *path) {
    hal_cm_init();
    hal_cm_input_close();
    hal_cm.input = semihost_open(path, 1u); /* "rb" */
    return hal_cm.input >= 0;
}

void hal_cm_input_close(void) {
    if (hal_cm.input >= 0) {
        semihost_close(hal_cm.input);
        hal_cm.input = -1;
    }
}

int32_t hal_cm_cmdline(char *buf, size_t cap) {
    hal_cm_init();
    return semihost_cmdline(buf, cap);
}

uint32_t hal_cycles(void) {
    hal_cm_init();
    return board_counter();
}

void hal_critical_enter(void) {
    uint32_t mask = cpu_primask();
    cpu_irq_disable();
    if (hal_cm.critical_depth == 0u) {
        hal_cm.critical_saved = mask;
    }
    hal_cm.critical_depth++;
}

void hal_critical_exit(void) {
    if (hal_cm.critical_depth == 0u) {
        return;
    }
    hal_cm.critical_depth--;
    if (hal_cm.critical_depth == 0u && hal_cm.critical_saved == 0u) {
        cpu_irq_enable();
    }
}

bool hal_ticks_start(const hal_ticks_config *config) {
    hal_cm_init();
    if (config == NULL || config->fast == NULL) {
        return false;
    }
    /* SysTick counts reload+1 clocks per period; 24-bit reload. */
    uint64_t clocks = (uint64_t)board_systick_hz() * config->fast_period_ns / 1000000000u;
    if (clocks < 2u || clocks > 0x01000000u) {
        return false;
    }
    hal_cm.ticks = *config;
    SCB_SHPR3 = (SCB_SHPR3 & 0x0000FFFFu) | (PRIO_FAST << 24) | (PRIO_MEDIUM << 16);
    NVIC_IPR8(board_soft_irq) = (uint8_t)PRIO_CONTROL;
    NVIC_ICPR(board_soft_irq) = NVIC_BIT(board_soft_irq);
    NVIC_ISER(board_soft_irq) = NVIC_BIT(board_soft_irq);
    SYST_CSR = 0u;
    SYST_RVR = (uint32_t)clocks - 1u;
    SYST_CVR = 0u;
    SYST_CSR = SYST_CSR_ENABLE | SYST_CSR_TICKINT | SYST_CSR_CLKSOURCE;
    return true;
}

void hal_ticks_stop(void) {
    SYST_CSR = 0u;
    SCB_ICSR = ICSR_PENDSTCLR | ICSR_PENDSVCLR;
    NVIC_ICPR(board_soft_irq) = NVIC_BIT(board_soft_irq);
}

void hal_medium_release(void) { SCB_ICSR = ICSR_PENDSVSET; }

void hal_control_release(void) { NVIC_ISPR(board_soft_irq) = NVIC_BIT(board_soft_irq); }

void hal_wait_for_tick(void) { cpu_wfi(); }

void SysTick_Handler(void);
void PendSV_Handler(void);
void Irq_Handler(void);
void Default_Handler(void);

/*
 * After the run's last tick: none follows, so one that fell due while the
 * last handler ran is not late, and is cleared.
 */
void hal_cm_fast_stop(void) {
    SYST_CSR = 0u;
    SCB_ICSR = ICSR_PENDSTCLR;
}

void hal_cm_fast_hold(bool hold) {
    if (hold) {
        hal_cm_held_csr = SYST_CSR & (SYST_CSR_ENABLE | SYST_CSR_TICKINT | SYST_CSR_CLKSOURCE);
        SYST_CSR = hal_cm_held_csr & ~SYST_CSR_ENABLE;
    } else {
        SYST_CSR = hal_cm_held_csr;
    }
}

void hal_cm_link_read(uint8_t *buf, size_t n) {
    hal_cm_init();
    for (size_t i = 0; i < n; i++) {
        int32_t c = board_uart_read();
        while (c < 0) {
            c = board_uart_read();
        }
        buf[i] = (uint8_t)c;
    }
}

uint32_t hal_cm_fast_overruns(void) { return hal_cm.fast_overruns; }

void hal_cm_stop_on_overrun(bool stop) { hal_cm.stop_on_overrun = stop; }

/* Kept out of line: the common path of the handler stays short. */
__attribute__((noinline)) static void fast_overrun(void) {
    hal_cm.fast_overruns++;
    if (hal_cm.stop_on_overrun) {
        SYST_CSR = 0u;
        SCB_ICSR = ICSR_PENDSTCLR;
    }
}

/*
 * The handler starts only after hal_ticks_start() has checked the
 * configuration, so the callback is set. The empty barrier at the end
 * keeps every call a call (not a tail jump), so that the handler returns
 * itself: its return instructions are where a tick ends for the
 * instruction counts (docs/firmware.md).
 */
void SysTick_Handler(void) {
    hal_cm.ticks.fast();
    if ((SCB_ICSR & ICSR_PENDSTSET) != 0u) {
        fast_overrun();
    }
    __asm__ volatile("" ::: "memory");
}

/*
 * The medium tick's overruns are the executive's to count: the task is
 * late when it is still busy at the next boundary, which the fast tick
 * sees. A pending PendSV here may be the next release, made on time.
 */
void PendSV_Handler(void) {
    if (hal_cm.ticks.medium != NULL) {
        hal_cm.ticks.medium();
    }
    /* An empty barrier: the call stays a call and the handler returns itself. */
    __asm__ volatile("" ::: "memory");
}

/*
 * Every external interrupt enters here (startup.c's table): the board's
 * software line runs the control tick; any other line is unexpected.
 */
void Irq_Handler(void) {
    if (cpu_ipsr() == 16u + board_soft_irq && hal_cm.ticks.control != NULL) {
        hal_cm.ticks.control();
    } else {
        Default_Handler();
    }
    __asm__ volatile("" ::: "memory");
}

void hal_exit(int status) {
    hal_cm_init();
    console_flush();
    semihost_exit(status);
}
