/*
 * Reset and exception entry for ARMv7-M: the vector table, the C run-time
 * set-up (copy .data from flash, clear .bss, enable the FPU where there is
 * one) and the fault handlers. A fault is reported on the console and ends
 * the run with status 3, so an emulator run never hangs on one.
 */
#include <stdint.h>

#include "armv7m.h"
#include "hal/hal.h"

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

/*
 * Reports a fault and ends the run. A fault can come at the deepest point
 * of the stack, so the report is built here in a small buffer rather than
 * with the formatter, whose frame is larger.
 */
static void fault_exit(const char *what) {
    static const char hex[] = "0123456789abcdef";
    char line[64];
    size_t n = 0;
    for (const char *p = "fatal: "; *p != '\0'; p++) {
        line[n++] = *p;
    }
    for (const char *p = what; *p != '\0' && n < 40u; p++) {
        line[n++] = *p;
    }
    for (const char *p = " (ICSR 0x"; *p != '\0'; p++) {
        line[n++] = *p;
    }
    uint32_t icsr = SCB_ICSR;
    for (int shift = 28; shift >= 0; shift -= 4) {
        line[n++] = hex[(icsr >> (unsigned)shift) & 0xFu];
    }
    line[n++] = ')';
    line[n++] = '\n';
    hal_console_write(line, n);
    hal_exit(3);
}

void HardFault_Handler(void) { fault_exit("fault exception"); }

void Default_Handler(void) { fault_exit("unexpected exception"); }
