/*
 * The HAL on ARMv7-M (Cortex-M3/M4/M7) under QEMU or on a board:
 *   - fast tick: SysTick, the highest priority;
 *   - medium tick: PendSV, the lowest exception priority, pended by the fast
 *     tick, so the fast tick preempts it;
 *   - background: thread mode, sleeping in WFI between ticks;
 *   - console: semihosting (buffered per line); telemetry: UART0;
 *   - exit: semihosting SYS_EXIT_EXTENDED, which carries the status.
 */
#include "armv7m.h"
#include "board.h"
#include "hal/hal.h"
#include "semihost.h"

/* Priorities as written to SHPR3 (upper bits significant on every core). */
#define PRIO_FAST 0x00u
#define PRIO_MEDIUM 0xFFu

static struct {
    bool initialised;
    int32_t console;   /* semihosting handle of ":tt", or -1 */
    char line[128];    /* console buffer, flushed per line */
    size_t line_len;
    hal_ticks_config ticks;
    uint32_t critical_depth;
    uint32_t critical_saved;
} hal_cm;

static void hal_cm_init(void) {
    if (!hal_cm.initialised) {
        hal_cm.initialised = true;
        board_init();
        hal_cm.console = semihost_open(":tt", 4u);
    }
}

static void console_flush(void) {
    if (hal_cm.line_len > 0u && hal_cm.console >= 0) {
        (void)semihost_write(hal_cm.console, hal_cm.line, hal_cm.line_len);
    }
    hal_cm.line_len = 0u;
}

void hal_console_write(const char *text, size_t n) {
    hal_cm_init();
    for (size_t i = 0; i < n; i++) {
        hal_cm.line[hal_cm.line_len++] = text[i];
        if (text[i] == '\n' || hal_cm.line_len == sizeof hal_cm.line) {
            console_flush();
        }
    }
}

void hal_telemetry_write(const uint8_t *data, size_t n) {
    hal_cm_init();
    board_uart_write(data, n);
}

size_t hal_input_read(uint8_t *buf, size_t n) {
    (void)buf;
    (void)n;
    return 0u;
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
    SYST_CSR = 0u;
    SYST_RVR = (uint32_t)clocks - 1u;
    SYST_CVR = 0u;
    SYST_CSR = SYST_CSR_ENABLE | SYST_CSR_TICKINT | SYST_CSR_CLKSOURCE;
    return true;
}

void hal_ticks_stop(void) {
    SYST_CSR = 0u;
    SCB_ICSR = ICSR_PENDSTCLR | ICSR_PENDSVCLR;
}

void hal_medium_release(void) { SCB_ICSR = ICSR_PENDSVSET; }

void hal_wait_for_tick(void) { cpu_wfi(); }

void SysTick_Handler(void);
void PendSV_Handler(void);

void SysTick_Handler(void) {
    if (hal_cm.ticks.fast != NULL) {
        hal_cm.ticks.fast();
    }
}

void PendSV_Handler(void) {
    if (hal_cm.ticks.medium != NULL) {
        hal_cm.ticks.medium();
    }
}

void hal_exit(int status) {
    hal_cm_init();
    console_flush();
    semihost_exit(status);
}
