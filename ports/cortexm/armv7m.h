/*
 * The few ARMv7-M system registers the port touches (architecture
 * reference manual, B3), as volatile lvalues. Kept local to the port.
 */
#ifndef UUV_ARMV7M_H
#define UUV_ARMV7M_H

#include <stdint.h>

#define REG32(addr) (*(volatile uint32_t *)(uintptr_t)(addr))

#define SCB_ICSR REG32(0xE000ED04u)       /* interrupt control and state */
#define SCB_VTOR REG32(0xE000ED08u)       /* vector table offset */
#define SCB_SHPR3 REG32(0xE000ED20u)      /* priorities of PendSV, SysTick */
#define SCB_CPACR REG32(0xE000ED88u)      /* coprocessor access (FPU) */
#define NVIC_ISER(n) REG32(0xE000E100u + 4u * ((n) / 32u)) /* interrupt set-enable */
#define NVIC_ISPR(n) REG32(0xE000E200u + 4u * ((n) / 32u)) /* interrupt set-pending */
#define NVIC_ICPR(n) REG32(0xE000E280u + 4u * ((n) / 32u)) /* interrupt clear-pending */
#define NVIC_IPR8(n) (*(volatile uint8_t *)(uintptr_t)(0xE000E400u + (n))) /* priority byte */
#define NVIC_BIT(n) (1u << ((n) % 32u))
#define SYST_CSR REG32(0xE000E010u)       /* SysTick control and status */
#define SYST_RVR REG32(0xE000E014u)       /* SysTick reload value */
#define SYST_CVR REG32(0xE000E018u)       /* SysTick current value */

#define ICSR_PENDSVSET (1u << 28)
#define ICSR_PENDSVCLR (1u << 27)
#define ICSR_PENDSTSET (1u << 26)
#define ICSR_PENDSTCLR (1u << 25)

#define SYST_CSR_ENABLE (1u << 0)
#define SYST_CSR_TICKINT (1u << 1)
#define SYST_CSR_CLKSOURCE (1u << 2) /* processor clock */

static inline void cpu_irq_disable(void) { __asm__ volatile("cpsid i" ::: "memory"); }
static inline void cpu_irq_enable(void) { __asm__ volatile("cpsie i" ::: "memory"); }
static inline void cpu_wfi(void) { __asm__ volatile("wfi" ::: "memory"); }
static inline void cpu_barrier(void) { __asm__ volatile("dsb\n\tisb" ::: "memory"); }

static inline uint32_t cpu_ipsr(void) {
    uint32_t v;
    __asm__ volatile("mrs %0, ipsr" : "=r"(v));
    return v;
}

static inline uintptr_t cpu_sp(void) {
    uintptr_t v;
    __asm__ volatile("mov %0, sp" : "=r"(v));
    return v;
}

static inline uint32_t cpu_primask(void) {
    uint32_t v;
    __asm__ volatile("mrs %0, primask" : "=r"(v));
    return v;
}

#endif /* UUV_ARMV7M_H */
