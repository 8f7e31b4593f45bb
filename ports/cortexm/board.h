/*
 * What differs between the supported machines, behind one small interface:
 * each machine links exactly one board_*.c (the Makefile chooses it).
 */
#ifndef UUV_BOARD_H
#define UUV_BOARD_H

#include <stddef.h>
#include <stdint.h>

/* Machine name, as reports print it. */
extern const char board_name[];

/* Brings up what the HAL needs: the free-running counter and the UART. */
void board_init(void);

/* [Hz] clock of SysTick (the processor clock). */
uint32_t board_systick_hz(void);

/* A free-running up-counter (its clock is the board's to choose); wraps modulo 2^32. */
uint32_t board_counter(void);

/*
 * An interrupt line no emulated device drives, pended by software to run
 * the control tick (hal_control_release). Within the vector table's 48.
 */
extern const uint32_t board_soft_irq;

/* Writes bytes to the machine's first UART (blocking). */
void board_uart_write(const uint8_t *data, size_t n);

/* The next byte the first UART received (0..255), or -1 when none is waiting. */
int32_t board_uart_read(void);

#endif /* UUV_BOARD_H */
