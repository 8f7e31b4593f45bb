/*
 * The Arm MPS2 FPGA images (AN385 Cortex-M3, AN386 Cortex-M4, AN500
 * Cortex-M7) as QEMU models them: a 25 MHz system clock, CMSDK APB timers
 * at 0x40000000 and 0x40001000, CMSDK UART0 at 0x40004000.
 */
#include "armv7m.h"
#include "board.h"

#define MPS2_CLOCK_HZ 25000000u

/* CMSDK APB timer 1, used as a free-running 32-bit down-counter. */
#define TIMER1_CTRL REG32(0x40001000u)
#define TIMER1_VALUE REG32(0x40001004u)
#define TIMER1_RELOAD REG32(0x40001008u)

/* CMSDK APB UART 0. */
#define UART0_DATA REG32(0x40004000u)
#define UART0_STATE REG32(0x40004004u)
#define UART0_CTRL REG32(0x40004008u)
#define UART0_BAUDDIV REG32(0x40004010u)
#define UART_STATE_TX_FULL (1u << 0)
#define UART_STATE_RX_FULL (1u << 1)
#define UART_CTRL_TX_EN (1u << 0)
#define UART_CTRL_RX_EN (1u << 1)

#ifndef BOARD_NAME
#error "the build must define BOARD_NAME (the QEMU machine name)"
#endif

const char board_name[] = BOARD_NAME;

/* IRQ 30: unused by the MPS2 FPGA images QEMU models. */
const uint32_t board_soft_irq = 30u;

void board_init(void) {
    TIMER1_RELOAD = 0xFFFFFFFFu;
    TIMER1_VALUE = 0xFFFFFFFFu;
    TIMER1_CTRL = 1u; /* enable, no interrupt */
    UART0_BAUDDIV = 16u;
    UART0_CTRL = UART_CTRL_TX_EN | UART_CTRL_RX_EN;
}

uint32_t board_systick_hz(void) { return MPS2_CLOCK_HZ; }

uint32_t board_counter(void) { return 0xFFFFFFFFu - TIMER1_VALUE; }

void board_uart_write(const uint8_t *data, size_t n) {
    for (size_t i = 0; i < n; i++) {
        while ((UART0_STATE & UART_STATE_TX_FULL) != 0u) {
        }
        UART0_DATA = data[i];
    }
}

int32_t board_uart_read(void) {
    return ((UART0_STATE & UART_STATE_RX_FULL) != 0u) ? (int32_t)(UART0_DATA & 0xFFu) : -1;
}
