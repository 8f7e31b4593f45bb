/*
 * Reset and exception entry for ARMv7-M: the vector table, the C run-time
 * set-up (copy .data from flash, clear .bss, enable the FPU where there is
 * one) and the fault handlers. A fault is reported on the console and ends
 * the run with status 3, so an emulator run never hangs on one.
 */
#include <stdint.h>

#include "armv7m.h"
#include "hal/hal.h"
#include "util/fmt.h"

/* Symbols from the linker script. */
extern uint32_t __data_load__[], __data_start__[], __data_end__[];
extern uint32_t __bss_start__[], __bss_end__[];
extern uint32_t __stack_top__[];

int main(void);
void Reset_Handler(void);
void Default_Handler(void);
void HardFault_Handler(void);
void NMI_Handler(void) __attribute__((weak, alias("Default_Handler")));
void MemManage_Handler(void) __attribute__((weak, alias("HardFault_Handler")));
void BusFault_Handler(void) __attribute__((weak, alias("HardFault_Handler")));
void UsageFault_Handler(void) __attribute__((weak, alias("HardFault_Handler")));
void SVC_Handler(void) __attribute__((weak, alias("Default_Handler")));
void PendSV_Handler(void) __attribute__((weak, alias("Default_Handler")));
void SysTick_Handler(void) __attribute__((weak, alias("Default_Handler")));
void Irq_Handler(void) __attribute__((weak, alias("Default_Handler")));

typedef void (*vector_fn)(void);

#define IRQ_COUNT 48
#define IRQ_X4 Irq_Handler, Irq_Handler, Irq_Handler, Irq_Handler
#define IRQ_X16 IRQ_X4, IRQ_X4, IRQ_X4, IRQ_X4

/* The table the core reads at reset: initial stack, then handlers. */
__attribute__((section(".vectors"), used)) const vector_fn vector_table[16 + IRQ_COUNT] = {
    (vector_fn)(uintptr_t)__stack_top__,
    Reset_Handler,
    NMI_Handler,
    HardFault_Handler,
    MemManage_Handler,
    BusFault_Handler,
    UsageFault_Handler,
    0,
    0,
    0,
    0,
    SVC_Handler,
    0,
    0,
    PendSV_Handler,
    SysTick_Handler,
    IRQ_X16, IRQ_X16, IRQ_X16,
};

void Reset_Handler(void) {
#if UUV_TARGET_HAS_FPU
    /* Full access to CP10 and CP11 before any floating-point instruction. */
    SCB_CPACR |= (0xFu << 20);
    cpu_barrier();
#endif
    const uint32_t *src = __data_load__;
    for (uint32_t *dst = __data_start__; dst < __data_end__;) {
        *dst++ = *src++;
    }
    for (uint32_t *dst = __bss_start__; dst < __bss_end__;) {
        *dst++ = 0u;
    }
    (void)main();
    hal_exit(0);
}

void HardFault_Handler(void) {
    fmt_print("fatal: fault exception (ICSR 0x%08lx)\n", (unsigned long)SCB_ICSR);
    hal_exit(3);
}

void Default_Handler(void) {
    fmt_print("fatal: unexpected exception (ICSR 0x%08lx)\n", (unsigned long)SCB_ICSR);
    hal_exit(3);
}
