// top.v: a board design whose program ROM never loads a word (its enable is tied low), so
// the team KCPSM6 executes zeros (LOAD s0, s0) forever on the board (test design for
// `botsim board --cpu iss`, which must notice that the ROM does not give the CPU the program
// it holds).
`timescale 1ns / 1ps
module top (
    input  wire        clk,
    input  wire        btnCpuReset,
    output wire [15:0] led
);
    wire [11:0] address;
    wire [17:0] instruction;
    wire [ 7:0] port_id, out_port;
    wire        bram_enable, write_strobe, k_write_strobe, read_strobe, interrupt_ack;
    reg  [ 7:0] leds = 8'h00;

    kcpsm6 cpu (
        .address(address), .instruction(instruction), .bram_enable(bram_enable),
        .in_port(8'h00), .out_port(out_port), .port_id(port_id),
        .write_strobe(write_strobe), .k_write_strobe(k_write_strobe), .read_strobe(read_strobe),
        .interrupt(1'b0), .interrupt_ack(interrupt_ack), .sleep(1'b0), .reset(~btnCpuReset),
        .clk(clk)
    );
    prog rom (.address(address), .instruction(instruction), .enable(1'b0), .clk(clk));

    always @(posedge clk) if (write_strobe) leds <= out_port;
    assign led = {8'h00, leds};

    wire [7:0] motctl = 8'h00;
    bot robot (.MotCtl_in(motctl), .LocX_reg(), .LocY_reg(), .Sensors_reg(), .BotInfo_reg(),
               .LMDist_reg(), .RMDist_reg(), .vid_row(10'd0), .vid_col(10'd0), .vid_pixel_out(),
               .clk(clk), .reset(~btnCpuReset), .upd_sysregs());
endmodule

// The program ROM's interface (botsim puts prog.psm in it: `--program prog.psm`).
module prog (
    input  wire [11:0] address,
    output reg  [17:0] instruction,
    input  wire        enable,
    input  wire        clk
);
    always @(posedge clk) if (enable) instruction <= 18'h00000;
endmodule
