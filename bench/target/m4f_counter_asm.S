/* Instruction counter of the Cortex-M4F timing benchmark (m4f_counter.c):
 * the vernier read of SysTick and the two hand-countable routines its
 * self-check measures.  Under QEMU with -icount shift=0 every executed
 * instruction advances the virtual clock by 1 ns and SysTick (CPU clock
 * source, 25 MHz on mps2-an386) decrements once per 40 ns, i.e. once per
 * 40 instructions. */
  .syntax unified
  .thumb
  .text

/* uint32_t m4f_vernier(uint32_t *first);
 * Reads SysTick's current value into *first, then reads it again once every
 * 41 instructions until two successive reads differ by 2 ticks instead of 1:
 * with reads 41 instructions apart the read phase within a 40-instruction
 * tick advances by exactly 1 per read, so the number of reads j (1..40) to
 * that step gives the phase of the first read.  Returns j, or 0 when no
 * step was seen within 64 reads (counter not running).
 * Loop body: 33 nops + adds, ldr, subs, mov, cmp, beq, cmp, blo = 41; from
 * the first read to the second: str, 5 nops, 33 nops, adds, ldr = 41. */
  .global m4f_vernier
  .type m4f_vernier, %function
  .thumb_func
m4f_vernier:
  push {r4, r5}
  ldr r1, =0xE000E018
  movs r3, #0
  ldr r2, [r1]
  str r2, [r0]
  .rept 5
  nop
  .endr
1:
  .rept 33
  nop
  .endr
  adds r3, r3, #1
  ldr r4, [r1]
  subs r5, r2, r4
  mov r2, r4
  cmp r5, #2
  beq 2f
  cmp r3, #64
  blo 1b
  movs r3, #0
2:
  mov r0, r3
  pop {r4, r5}
  bx lr
  .size m4f_vernier, . - m4f_vernier
  .ltorg

/* void m4f_count_empty(void *unused): one instruction. */
  .global m4f_count_empty
  .type m4f_count_empty, %function
  .thumb_func
m4f_count_empty:
  bx lr
  .size m4f_count_empty, . - m4f_count_empty

/* void m4f_count_loop(void *n), n = (void *)(uintptr_t)count, count >= 1: subs/bne n times, then bx lr:
 * 2 n + 1 instructions. */
  .global m4f_count_loop
  .type m4f_count_loop, %function
  .thumb_func
m4f_count_loop:
1:
  subs r0, r0, #1
  bne 1b
  bx lr
  .size m4f_count_loop, . - m4f_count_loop
