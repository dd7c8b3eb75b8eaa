// bot_tb.v: a plain Verilog testbench of `bot` for a second simulator (Icarus Verilog).
//
// No reset pulse (the core self-starts, as after configuration), MotCtl_in = MOTCTL from the
// start, and one CSV line per upd_sysregs pulse in the format of `botsim run --trace-csv`:
// sample, the first cycle the pulse is high, LocX, LocY, BotInfo, Sensors, LMDist, RMDist.
// Cycle c is the c-th clock period (rising edge at 10c + 5 ns), as in the Verilator model.
`timescale 1ns / 1ps
module bot_tb #(
    parameter WORLD = "",
    parameter [7:0] MOTCTL = 8'h33,
    parameter integer SAMPLES = 10,
    parameter integer MAX_CYCLES = 1000000
);
    reg clk = 1'b0;
    reg reset = 1'b0;
    wire [7:0] locx, locy, sensors, botinfo, lmdist, rmdist;
    wire [1:0] pixel;
    wire upd;

    bot #(.WORLD_FILE(WORLD)) dut (
        .MotCtl_in(MOTCTL), .LocX_reg(locx), .LocY_reg(locy), .Sensors_reg(sensors),
        .BotInfo_reg(botinfo), .LMDist_reg(lmdist), .RMDist_reg(rmdist),
        .vid_row(10'd0), .vid_col(10'd0), .vid_pixel_out(pixel),
        .clk(clk), .reset(reset), .upd_sysregs(upd)
    );

    always #5 clk = ~clk;

    integer cycle = 0;
    integer sample = 0;
    reg upd_before = 1'b0;

    // At each falling edge (time 10c) the outputs are those of cycle c.
    always @(negedge clk) begin
        cycle = cycle + 1;
        if (upd === 1'b1 && upd_before !== 1'b1) begin
            $display("%0d,%0d,%0d,%0d,%0d,%0d,%0d,%0d", sample, cycle, locx, locy, botinfo, sensors, lmdist, rmdist);
            if (sample == SAMPLES) $finish;
            sample = sample + 1;
        end
        if (^{locx, locy, sensors, botinfo, lmdist, rmdist, upd} === 1'bx) begin
            $display("ERROR: X on an output in cycle %0d", cycle);
            $finish;
        end
        upd_before = upd;
        if (cycle == MAX_CYCLES) begin
            $display("ERROR: no upd_sysregs pulse for sample %0d within %0d cycles", sample, MAX_CYCLES);
            $finish;
        end
    end
endmodule
