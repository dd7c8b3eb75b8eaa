// botsim_clkgen.v: one generated clock of a board simulation (not synthesizable).
//
// The board harness finds every instance by its public variables, computes the clock's edges
// from PERIOD_NUM / PERIOD_DEN (the period in picoseconds, as a fraction, so 65 MHz has no
// drift), PHASE_MDEG (millidegrees) and DUTY_PERMILLE, and writes `q` at those instants
// while `run` is high. Every edge falls at its true time, rounded to the picosecond, on a
// grid that starts at time 0: clocks derived from one input stay aligned with it.
`timescale 1ns / 1ps
module botsim_clkgen #(
    parameter integer PERIOD_NUM = 10000,
    parameter integer PERIOD_DEN = 1,
    parameter integer PHASE_MDEG = 0,
    parameter integer DUTY_PERMILLE = 500
) (
    input  wire run,
    output wire clk
);
    reg q /*verilator public_flat_rw*/ = 1'b0;
    wire running /*verilator public_flat_rd*/ = run;
    integer botsim_period_num /*verilator public_flat_rd*/ = PERIOD_NUM;
    integer botsim_period_den /*verilator public_flat_rd*/ = PERIOD_DEN;
    integer botsim_phase_mdeg /*verilator public_flat_rd*/ = PHASE_MDEG;
    integer botsim_duty_permille /*verilator public_flat_rd*/ = DUTY_PERMILLE;
    assign clk = q;
endmodule
