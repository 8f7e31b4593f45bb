/*
 * The STM32F405 of QEMU's netduinoplus2 board: a 168 MHz processor clock
 * (SysTick counts it), the general-purpose timer TIM2 (32 bits, at
 * 0x40000000) as the free-running counter, and USART1 (at 0x40011000,
 * QEMU's first serial port) for telemetry. Addresses and bits from the
 * STM32F405 reference manual (RM0090).
 */
#include "armv7m.h"
#include "board.h"

#define STM32_SYSCLK_HZ 168000000u

/* TIM2, counting up over its full 32-bit range. */
#define TIM2_CR1 REG32(0x40000000u)
#define TIM2_EGR REG32(0x40000014u)
#define TIM2_CNT REG32(0x40000024u)
#define TIM2_PSC REG32(0x40000028u)
#define TIM2_ARR REG32(0x4000002Cu)
#define TIM_CR1_CEN (1u << 0)
#define TIM_EGR_UG (1u << 0)

/* USART1. */
#define USART1_SR REG32(0x40011000u)
#define USART1_DR REG32(0x40011004u)
#define USART1_BRR REG32(0x40011008u)
#define USART1_CR1 REG32(0x4001100Cu)
#define USART_SR_TXE (1u << 7)
#define USART_CR1_UE (1u << 13)
#define USART_CR1_TE (1u << 3)
#define USART_CR1_RE (1u << 2)
#define USART_SR_RXNE (1u << 5)

#ifndef BOARD_NAME
#error "the build must define BOARD_NAME (the QEMU machine name)"
#endif

const char board_name[] = BOARD_NAME;

/* IRQ 47 (DMA1 stream 7 on the STM32F405): QEMU models no DMA. */
const uint32_t board_soft_irq = 47u;

void board_init(void) {
    TIM2_PSC = 0u;
    TIM2_ARR = 0xFFFFFFFFu;
    TIM2_EGR = TIM_EGR_UG; /* load the prescaler */
    TIM2_CR1 = TIM_CR1_CEN;
    USART1_BRR = 0x16Du; /* 115200 baud at 42 MHz (APB2 / 2); QEMU ignores it */
    USART1_CR1 = USART_CR1_UE | USART_CR1_TE | USART_CR1_RE;
}

uint32_t board_systick_hz(void) { return STM32_SYSCLK_HZ; }

uint32_t board_counter(void) { return TIM2_CNT; }

void board_uart_write(const uint8_t *data, size_t n) {
    for (size_t i = 0; i < n; i++) {
        while ((USART1_SR & USART_SR_TXE) == 0u) {
        }
        USART1_DR = data[i];
    }
}

int32_t board_uart_read(void) {
    return ((USART1_SR & USART_SR_RXNE) != 0u) ? (int32_t)(USART1_DR & 0xFFu) : -1;
}
