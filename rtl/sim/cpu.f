# The KCPSM6 test harness (the CPU lock-step's device under test), as rtl/bot.f.
rtl/kcpsm6.vlt
rtl/kcpsm6.v
rtl/sim/kcpsm6_harness.v
rtl/sim/kcpsm6_harness.vlt
