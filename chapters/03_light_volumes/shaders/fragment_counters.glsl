// Exact 64-bit fragment counts (chapter 03's, and chapter 04's capsules'), included by the
// shaders that count when COUNT_FRAGMENTS is defined. C++: fragment_counters.h.
// [count64]
// GLSL has no 64-bit atomic counters everywhere (llvmpipe has none), and a 32-bit one wraps
// past 4 294 967 295: 65 536 lights at 1080p shade more. So each counter is a {lo, hi} pair
// of 32-bit words. atomicAdd returns the value before the add, so exactly one invocation sees
// lo at 0xFFFFFFFF, the one that wraps it to 0: that one alone carries into hi. Once the
// pass is done, lo + 2^32 hi is the exact count.
struct FragmentCounter {
  uint lo;
  uint hi;
};
layout(std430, binding = FRAGMENT_COUNTERS_BINDING) buffer FragmentCounters { FragmentCounter fragment_counters[]; };
uniform int u_counter_base;  // this draw's first counter (0; chapter 04: one set per tube)

void count_fragment(uint counter) {
  uint i = uint(u_counter_base) + counter;
  if (atomicAdd(fragment_counters[i].lo, 1u) == 0xFFFFFFFFu) atomicAdd(fragment_counters[i].hi, 1u);
}
// [/count64]
