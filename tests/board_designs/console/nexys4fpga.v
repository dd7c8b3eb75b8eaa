// nexys4fpga.v: a final-project-shaped console (clean-room, written for botsim's tests from
// spec board.md 1, 2 and 7): the team's PicoBlaze runs console.psm. It greets on the USB-UART
// (115200 baud, 8N1), then echoes every byte it receives; each scan code the keyboard sends
// goes to the LEDs (7-0 the last code, 15-8 the one before) and the count of keys pressed to
// the seven-segment display (hexadecimal). Switch 0 holds the keyboard's clock low (the
// host inhibits it); the receivers' error counts are on input ports for the program.
`timescale 1ns / 1ps
module nexys4fpga (
    input  wire        clk,
    input  wire        btnCpuReset,
    input  wire [15:0] sw,
    output wire [15:0] led,
    output wire [ 6:0] seg,
    output wire        dp,
    output wire [ 7:0] an,
    input  wire        RsRx,
    output wire        RsTx,
    inout  wire        PS2_CLK,
    inout  wire        PS2_DATA
);
    wire [ 5:0] db_pbtns;
    wire [15:0] db_sw;
    wire        sysreset = ~db_pbtns[0];
    debounce #(.RESET_POLARITY_LOW(1), .SIMULATE(1)) DB (
        .clk(clk), .pbtn_in({5'd0, btnCpuReset}), .switch_in(sw), .pbtn_db(db_pbtns), .swtch_db(db_sw)
    );

    wire [11:0] address;
    wire [17:0] instruction;
    wire        bram_enable, rdl;
    wire [ 7:0] port_id, out_port;
    reg  [ 7:0] in_port = 8'd0;
    wire        write_strobe, k_write_strobe, read_strobe, interrupt_ack;
    kcpsm6 #(.interrupt_vector(12'h3FF), .scratch_pad_memory_size(64), .hwbuild(8'h00)) CONSOLECPU (
        .address(address), .instruction(instruction), .bram_enable(bram_enable),
        .port_id(port_id), .write_strobe(write_strobe), .k_write_strobe(k_write_strobe),
        .out_port(out_port), .read_strobe(read_strobe), .in_port(in_port),
        .interrupt(1'b0), .interrupt_ack(interrupt_ack), .sleep(1'b0),
        .reset(sysreset | rdl), .clk(clk)
    );
    console PGM (.enable(bram_enable), .address(address), .instruction(instruction), .rdl(rdl), .clk(clk));

    // The UART: a received byte waits in `rx_byte` until the program reads port 01.
    wire [7:0] rx_data, rx_errors;
    wire rx_valid, tx_busy;
    reg [7:0] rx_byte = 8'd0;
    reg rx_full = 1'b0;
    uart_rx RX (.clk(clk), .rx(RsRx), .data(rx_data), .valid(rx_valid), .errors(rx_errors));
    uart_tx TX (.clk(clk), .start(write_strobe && port_id == 8'h01), .data(out_port), .tx(RsTx), .busy(tx_busy));

    // The keyboard: a scan code waits in `key_byte` until the program reads port 03.
    wire [7:0] kbd_data, kbd_errors;
    wire kbd_valid;
    reg [7:0] key_byte = 8'd0;
    reg key_full = 1'b0;
    ps2_rx KBD (.clk(clk), .inhibit(db_sw[0]), .ps2_clk(PS2_CLK), .ps2_data(PS2_DATA),
                .data(kbd_data), .valid(kbd_valid), .errors(kbd_errors));

    reg [15:0] leds = 16'd0;
    reg [15:0] count = 16'd0;
    always @(posedge clk) begin
        case (port_id)
            8'h00: in_port <= {6'd0, tx_busy, rx_full};
            8'h01: in_port <= rx_byte;
            8'h02: in_port <= {7'd0, key_full};
            8'h03: in_port <= key_byte;
            8'h04: in_port <= rx_errors;
            8'h05: in_port <= kbd_errors;
            default: in_port <= 8'h00;
        endcase
        if (rx_valid) begin
            rx_byte <= rx_data;
            rx_full <= 1'b1;
        end else if (read_strobe && port_id == 8'h01) begin
            rx_full <= 1'b0;
        end
        if (kbd_valid) begin
            key_byte <= kbd_data;
            key_full <= 1'b1;
        end else if (read_strobe && port_id == 8'h03) begin
            key_full <= 1'b0;
        end
        if (write_strobe) begin
            case (port_id)
                8'h02: leds[7:0] <= out_port;
                8'h12: leds[15:8] <= out_port;
                8'h06: count[7:0] <= out_port;
                8'h07: count[15:8] <= out_port;
                default: ;
            endcase
        end
    end
    assign led = leds;

    sevensegment #(.RESET_POLARITY_LOW(0), .SIMULATE(1)) SSB (
        .clk(clk), .reset(sysreset),
        .d7(5'h17), .d6(5'h17), .d5(5'h17), .d4(5'h17),
        .d3({1'b0, count[15:12]}), .d2({1'b0, count[11:8]}), .d1({1'b0, count[7:4]}), .d0({1'b0, count[3:0]}),
        .dp(8'h00), .seg({dp, seg}), .an(an), .digits_out()
    );
endmodule
