/*
 * The Stellaris LM3S6965 of QEMU's lm3s6965evb board: a 12.5 MHz
 * processor clock at reset (SysTick counts it), UART0 (a PL011 at
 * 0x4000C000) for telemetry. QEMU's general-purpose timers cannot be read
 * back, so the free-running counter is the watchdog's value register (at
 * 0x40000000), counting down at the processor clock: its interrupt is
 * never enabled in the NVIC and its reset stays disabled, so it only
 * counts. Addresses and bits from the LM3S6965 data sheet.
 */
#include "armv7m.h"
#include "board.h"

#define LM3S_SYSCLK_HZ 12500000u

/* Watchdog 0. */
#define WDT_LOAD REG32(0x40000000u)
#define WDT_VALUE REG32(0x40000004u)
#define WDT_CTL REG32(0x40000008u)
#define WDT_CTL_INTEN (1u << 0) /* starts the counter */

/* UART0 (PL011). */
#define UART0_DR REG32(0x4000C000u)
#define UART0_FR REG32(0x4000C018u)
#define UART0_IBRD REG32(0x4000C024u)
#define UART0_FBRD REG32(0x4000C028u)
#define UART0_LCRH REG32(0x4000C02Cu)
#define UART0_CTL REG32(0x4000C030u)
#define UART_FR_TXFF (1u << 5)
#define UART_LCRH_WLEN8 (3u << 5)
#define UART_CTL_UARTEN (1u << 0)
#define UART_CTL_TXE (1u << 8)
#define UART_CTL_RXE (1u << 9)
#define UART_FR_RXFE (1u << 4)

#ifndef BOARD_NAME
#error "the build must define BOARD_NAME (the QEMU machine name)"
#endif

const char board_name[] = BOARD_NAME;

/* IRQ 47: beyond the peripherals QEMU models on the LM3S6965. */
const uint32_t board_soft_irq = 47u;

void board_init(void) {
    WDT_LOAD = 0xFFFFFFFFu;
    WDT_CTL = WDT_CTL_INTEN;
    UART0_IBRD = 6u; /* 115200 baud at 12.5 MHz: 6 + 50/64; QEMU ignores it */
    UART0_FBRD = 50u;
    UART0_LCRH = UART_LCRH_WLEN8;
    UART0_CTL = UART_CTL_UARTEN | UART_CTL_TXE | UART_CTL_RXE;
}

uint32_t board_systick_hz(void) { return LM3S_SYSCLK_HZ; }

uint32_t board_counter(void) { return 0xFFFFFFFFu - WDT_VALUE; }

void board_uart_write(const uint8_t *data, size_t n) {
    for (size_t i = 0; i < n; i++) {
        while ((UART0_FR & UART_FR_TXFF) != 0u) {
        }
        UART0_DR = data[i];
    }
}

int32_t board_uart_read(void) {
    return ((UART0_FR & UART_FR_RXFE) == 0u) ? (int32_t)(UART0_DR & 0xFFu) : -1;
}
