// top.v: a KCPSM6 in a wait loop beside a display refresh counter of 2^16 clocks, as
// tests/board_designs/phases, plus a 25 MHz pixel clock from an MMCM driving a "frame"
// counter of 1,000 pixel clocks (test design for botsim board's fast-forward): the two
// counters repeat together only every 8.2 M clocks, more than a sample. With FEEDBACK 0 the
// frame counter drives the VGA pins alone, which a run without frames does not record: the
// fast-forward compares and puts back the rest and skips. With FEEDBACK 1 each frame also
// toggles LED 15, so the pixel clock drives what the run records and every edge is simulated.
`timescale 1ns / 1ps
module top #(
    parameter FEEDBACK = 0
) (
    input  wire        clk,
    input  wire        btnCpuReset,
    output wire [ 7:0] an,
    output wire [ 6:0] seg,
    output wire [15:0] led,
    output wire [ 3:0] vgaRed,
    output wire        Hsync
);
    wire [11:0] address;
    wire [17:0] instruction;
    wire [ 7:0] port_id, out_port;
    wire        bram_enable, write_strobe, k_write_strobe, read_strobe, interrupt_ack;
    wire        upd_sysregs;
    reg         interrupt = 1'b0;
    reg  [ 7:0] count = 8'h00;
    reg  [15:0] refresh = 16'd0;

    kcpsm6 cpu (
        .address(address), .instruction(instruction), .bram_enable(bram_enable),
        .in_port(8'h00), .out_port(out_port), .port_id(port_id),
        .write_strobe(write_strobe), .k_write_strobe(k_write_strobe), .read_strobe(read_strobe),
        .interrupt(interrupt), .interrupt_ack(interrupt_ack), .sleep(1'b0), .reset(~btnCpuReset),
        .clk(clk)
    );
    phases rom (.address(address), .instruction(instruction), .enable(bram_enable), .clk(clk));

    always @(posedge clk) begin
        if (write_strobe) count <= out_port;
        if (interrupt_ack) interrupt <= 1'b0;
        else if (upd_sysregs) interrupt <= 1'b1;
        refresh <= refresh + 16'd1;
    end
    assign an  = ~(8'h01 << refresh[15:13]);
    assign seg = {count[2:0], refresh[15:13], 1'b0};

    // The pixel clock: 100 MHz x 10 / 40, through BUFGs as a Clocking Wizard wires it.
    wire clk_in, clk25_unbuf, clk25, fb_unbuf, fb, locked;
    IBUF ib (.I(clk), .O(clk_in));
    MMCME2_ADV #(
        .BANDWIDTH("OPTIMIZED"), .CLKOUT4_CASCADE("FALSE"), .COMPENSATION("ZHOLD"),
        .STARTUP_WAIT("FALSE"), .DIVCLK_DIVIDE(1), .CLKFBOUT_MULT_F(10.000),
        .CLKFBOUT_PHASE(0.000), .CLKFBOUT_USE_FINE_PS("FALSE"), .CLKOUT0_DIVIDE_F(40.000),
        .CLKOUT0_PHASE(0.000), .CLKOUT0_DUTY_CYCLE(0.500), .CLKOUT0_USE_FINE_PS("FALSE"),
        .CLKIN1_PERIOD(10.0)
    ) mmcm (
        .CLKFBOUT(fb_unbuf), .CLKFBOUTB(), .CLKOUT0(clk25_unbuf), .CLKOUT0B(),
        .CLKOUT1(), .CLKOUT1B(), .CLKOUT2(), .CLKOUT2B(), .CLKOUT3(), .CLKOUT3B(),
        .CLKOUT4(), .CLKOUT5(), .CLKOUT6(),
        .CLKFBIN(fb), .CLKIN1(clk_in), .CLKIN2(1'b0), .CLKINSEL(1'b1),
        .DADDR(7'h0), .DCLK(1'b0), .DEN(1'b0), .DI(16'h0), .DO(), .DRDY(), .DWE(1'b0),
        .PSCLK(1'b0), .PSEN(1'b0), .PSINCDEC(1'b0), .PSDONE(),
        .LOCKED(locked), .CLKINSTOPPED(), .CLKFBSTOPPED(), .PWRDWN(1'b0), .RST(1'b0)
    );
    BUFG fbbuf (.I(fb_unbuf), .O(fb));
    BUFG outbuf (.I(clk25_unbuf), .O(clk25));

    reg [9:0] pixel = 10'd0;
    reg       frame = 1'b0;
    always @(posedge clk25) begin
        if (pixel == 10'd999) begin
            pixel <= 10'd0;
            frame <= ~frame;
        end else begin
            pixel <= pixel + 10'd1;
        end
    end
    assign vgaRed = pixel[3:0];
    assign Hsync = pixel[9];
    assign led = {FEEDBACK != 0 ? frame : 1'b0, 7'h00, count};

    bot robot (.MotCtl_in(8'h33), .LocX_reg(), .LocY_reg(), .Sensors_reg(), .BotInfo_reg(),
               .LMDist_reg(), .RMDist_reg(), .vid_row(10'd0), .vid_col(10'd0), .vid_pixel_out(),
               .clk(clk), .reset(~btnCpuReset), .upd_sysregs(upd_sysregs));
    wire unused_ok = &{1'b0, locked, 1'b0};
endmodule

// The program ROM's interface (botsim puts a program in it: `--program phases.psm`).
module phases (
    input  wire [11:0] address,
    output reg  [17:0] instruction,
    input  wire        enable,
    input  wire        clk
);
    always @(posedge clk) if (enable) instruction <= 18'h00000;
endmodule
