// final_top.v: a final project as a team commits it (clean-room, written for botsim's tests):
// a Nexys4 DDR design whose pins carry that board's master .xdc names. Two PicoBlazes: the
// console's (console.psm: a greeting and an echo on the USB-UART, the keyboard's scan codes)
// and the tilt reader's (tilt.psm: the ADXL362 over SPI); the switches play a note on the
// audio output. LED 15-8 the accelerometer's x, 7-0 the last scan code; the display counts
// the keys pressed.
`timescale 1ns / 1ps
module final_top (
    input  wire        CLK100MHZ,
    input  wire        CPU_RESETN,
    input  wire [15:0] SW,
    output wire [15:0] LED,
    output wire        CA, CB, CC, CD, CE, CF, CG, DP,
    output wire [ 7:0] AN,
    input  wire        UART_TXD_IN,
    output wire        UART_RXD_OUT,
    inout  wire        PS2_CLK,
    inout  wire        PS2_DATA,
    output wire        ACL_SCLK,
    output wire        ACL_MOSI,
    input  wire        ACL_MISO,
    output wire        ACL_CSN,
    output wire        AUD_PWM,
    output wire        AUD_SD
);
    wire clk = CLK100MHZ;
    wire [5:0] db_pbtns;
    wire [15:0] db_sw;
    wire sysreset = ~db_pbtns[0];
    debounce #(.RESET_POLARITY_LOW(1), .SIMULATE(1)) DB (
        .clk(clk), .pbtn_in({5'd0, CPU_RESETN}), .switch_in(SW), .pbtn_db(db_pbtns), .swtch_db(db_sw)
    );

    // The console's CPU.
    wire [11:0] c_address;
    wire [17:0] c_instruction;
    wire c_enable, c_rdl, c_write, c_kwrite, c_read, c_ack;
    wire [7:0] c_port, c_out;
    reg  [7:0] c_in = 8'd0;
    kcpsm6 #(.interrupt_vector(12'h3FF), .scratch_pad_memory_size(64), .hwbuild(8'h00)) CONSOLE_CPU (
        .address(c_address), .instruction(c_instruction), .bram_enable(c_enable), .port_id(c_port),
        .write_strobe(c_write), .k_write_strobe(c_kwrite), .out_port(c_out), .read_strobe(c_read),
        .in_port(c_in), .interrupt(1'b0), .interrupt_ack(c_ack), .sleep(1'b0), .reset(sysreset | c_rdl), .clk(clk)
    );
    console CONSOLE_ROM (.enable(c_enable), .address(c_address), .instruction(c_instruction), .rdl(c_rdl), .clk(clk));

    wire [7:0] rx_data, rx_errors, kbd_data, kbd_errors;
    wire rx_valid, tx_busy, kbd_valid;
    reg [7:0] rx_byte = 8'd0, key_byte = 8'd0;
    reg rx_full = 1'b0, key_full = 1'b0;
    uart_rx RX (.clk(clk), .rx(UART_TXD_IN), .data(rx_data), .valid(rx_valid), .errors(rx_errors));
    uart_tx TX (.clk(clk), .start(c_write && c_port == 8'h01), .data(c_out), .tx(UART_RXD_OUT), .busy(tx_busy));
    ps2_rx KBD (.clk(clk), .inhibit(1'b0), .ps2_clk(PS2_CLK), .ps2_data(PS2_DATA),
                .data(kbd_data), .valid(kbd_valid), .errors(kbd_errors));
    reg [7:0] code = 8'd0;
    reg [15:0] keys = 16'd0;
    always @(posedge clk) begin
        case (c_port)
            8'h00: c_in <= {6'd0, tx_busy, rx_full};
            8'h01: c_in <= rx_byte;
            8'h02: c_in <= {7'd0, key_full};
            8'h03: c_in <= key_byte;
            default: c_in <= 8'h00;
        endcase
        if (rx_valid) {rx_byte, rx_full} <= {rx_data, 1'b1};
        else if (c_read && c_port == 8'h01) rx_full <= 1'b0;
        if (kbd_valid) {key_byte, key_full} <= {kbd_data, 1'b1};
        else if (c_read && c_port == 8'h03) key_full <= 1'b0;
        if (c_write && c_port == 8'h02) code <= c_out;
        if (c_write && c_port == 8'h06) keys[7:0] <= c_out;
        if (c_write && c_port == 8'h07) keys[15:8] <= c_out;
    end

    // The tilt reader's CPU.
    wire [11:0] t_address;
    wire [17:0] t_instruction;
    wire t_enable, t_rdl, t_write, t_kwrite, t_read, t_ack;
    wire [7:0] t_port, t_out;
    reg  [7:0] t_in = 8'd0;
    kcpsm6 #(.interrupt_vector(12'h3FF), .scratch_pad_memory_size(64), .hwbuild(8'h01)) TILT_CPU (
        .address(t_address), .instruction(t_instruction), .bram_enable(t_enable), .port_id(t_port),
        .write_strobe(t_write), .k_write_strobe(t_kwrite), .out_port(t_out), .read_strobe(t_read),
        .in_port(t_in), .interrupt(1'b0), .interrupt_ack(t_ack), .sleep(1'b0), .reset(sysreset | t_rdl), .clk(clk)
    );
    tilt TILT_ROM (.enable(t_enable), .address(t_address), .instruction(t_instruction), .rdl(t_rdl), .clk(clk));
    wire [7:0] spi_rx;
    wire spi_busy;
    reg cs = 1'b1;
    reg [7:0] x8 = 8'd0;
    spi_master SPI (.clk(clk), .start(t_write && t_port == 8'h10), .tx(t_out), .rx(spi_rx), .busy(spi_busy),
                    .sck(ACL_SCLK), .mosi(ACL_MOSI), .miso(ACL_MISO));
    always @(posedge clk) begin
        t_in <= t_port == 8'h11 ? {7'd0, spi_busy} : spi_rx;
        if (t_write && t_port == 8'h11) cs <= t_out[0];
        if (t_write && t_port == 8'h12) x8 <= t_out;
    end
    assign ACL_CSN = cs;
    assign LED = {x8, code};

    // A note from switches 2-0 (C4, A4 at 5, C5 at 7, else G4), heard while switch 15 is on:
    // a square wave, its half period in clocks.
    reg [17:0] half;
    always @(*) begin
        case (db_sw[2:0])
            3'd0: half = 18'd190840;
            3'd5: half = 18'd113636;
            3'd7: half = 18'd95602;
            default: half = 18'd127551;
        endcase
    end
    reg [17:0] count = 18'd0;
    reg wave = 1'b0;
    always @(posedge clk) begin
        if (count + 18'd1 >= half) begin
            count <= 18'd0;
            wave <= !wave;
        end else begin
            count <= count + 18'd1;
        end
    end
    assign AUD_PWM = wave ? 1'bz : 1'b0;
    assign AUD_SD = db_sw[15];

    wire [7:0] seg8;
    sevensegment #(.RESET_POLARITY_LOW(0), .SIMULATE(1)) SSB (
        .clk(clk), .reset(sysreset),
        .d7(5'h17), .d6(5'h17), .d5(5'h17), .d4(5'h17),
        .d3({1'b0, keys[15:12]}), .d2({1'b0, keys[11:8]}), .d1({1'b0, keys[7:4]}), .d0({1'b0, keys[3:0]}),
        .dp(8'h00), .seg(seg8), .an(AN), .digits_out()
    );
    assign {DP, CG, CF, CE, CD, CC, CB, CA} = seg8;
endmodule
