// world_if.v: BotSim 2.0's I/O ports between the KCPSM6 and the outside world (spec 8).
//
// Sixteen ports, decoded from AddrIn[3:0] (port numbers alias every 16):
//   0 MotCtl_in (read)          8 MapX, column (read/write)
//   1 LocX   2 LocY             9 MapY, row (read/write)
//   3 BotInfo 4 Sensors         A map value {6'b0, MapVal} (read)
//   5 LMDist 6 RMDist           C toggle load_sys_regs   D toggle load_dist_regs
//     (holding registers)       E toggle upd_sysregs     7 B F reserved (read 0)
//
// Two-phase load (spec 8.3): the program writes the holding registers, then writes port C
// twice back-to-back; each write toggles load_sys_regs, so it is high for 2 clocks and the
// four visible registers change together. Port D does the same for the distance registers,
// port E makes the 2-clock upd_sysregs pulse.
//
// Reads come from a registered mux updated every clock (Rd_Strobe is not needed: kcpsm6
// samples in_port at the end of INPUT's second cycle). Reset is synchronous and clears the
// holding and visible registers and the three toggles, not MapX, MapY or DataOut.
`timescale 1ns / 1ps
module world_if (
    input  wire       Wr_Strobe,
    input  wire       Rd_Strobe,
    input  wire [7:0] AddrIn,
    input  wire [7:0] DataIn,
    output reg  [7:0] DataOut = 8'h00,
    input  wire [7:0] MotCtl,
    output reg  [7:0] LocX = 8'h00,
    output reg  [7:0] LocY = 8'h00,
    output reg  [7:0] BotInfo = 8'h00,
    output reg  [7:0] Sensors = 8'h00,
    output reg  [7:0] LMDist = 8'h00,
    output reg  [7:0] RMDist = 8'h00,
    output reg  [7:0] MapX = 8'h00,
    output reg  [7:0] MapY = 8'h00,
    input  wire [1:0] MapVal,
    input  wire       clk,
    input  wire       reset,
    output reg        upd_sysregs = 1'b0
);
    localparam [3:0] PRD_MOTCTL_IN  = 4'h0, PWR_LOCX = 4'h1, PWR_LOCY = 4'h2, PWR_BOTINFO = 4'h3,
                     PWR_SENSORS    = 4'h4, PWR_LMDIST = 4'h5, PWR_RMDIST = 4'h6,
                     PWR_COLADR     = 4'h8, PWR_ROWADR = 4'h9, PRD_LOCINFO = 4'hA,
                     PRW_LOADREGS   = 4'hC, PRW_LDMOTDIST = 4'hD, PRW_UPDSYSREGS = 4'hE;

    wire [3:0] port = AddrIn[3:0];

    reg [7:0] locx_h = 8'h00, locy_h = 8'h00, botinfo_h = 8'h00, sensors_h = 8'h00;
    reg [7:0] lmdist_h = 8'h00, rmdist_h = 8'h00;
    reg       load_sys_regs = 1'b0, load_dist_regs = 1'b0;

    // Registered read mux.
    always @(posedge clk) begin
        case (port)
            PRD_MOTCTL_IN: DataOut <= MotCtl;
            PWR_LOCX:      DataOut <= locx_h;
            PWR_LOCY:      DataOut <= locy_h;
            PWR_BOTINFO:   DataOut <= botinfo_h;
            PWR_SENSORS:   DataOut <= sensors_h;
            PWR_LMDIST:    DataOut <= lmdist_h;
            PWR_RMDIST:    DataOut <= rmdist_h;
            PWR_COLADR:    DataOut <= MapX;
            PWR_ROWADR:    DataOut <= MapY;
            PRD_LOCINFO:   DataOut <= {6'b000000, MapVal};
            default:       DataOut <= 8'h00;
        endcase
    end

    // Map address registers (not reset).
    always @(posedge clk) begin
        if (Wr_Strobe && port == PWR_COLADR) MapX <= DataIn;
        if (Wr_Strobe && port == PWR_ROWADR) MapY <= DataIn;
    end

    // Holding registers and the three toggles.
    always @(posedge clk) begin
        if (reset) begin
            {locx_h, locy_h, botinfo_h, sensors_h, lmdist_h, rmdist_h} <= 48'd0;
            load_sys_regs <= 1'b0;
            load_dist_regs <= 1'b0;
            upd_sysregs <= 1'b0;
        end else if (Wr_Strobe) begin
            case (port)
                PWR_LOCX:       locx_h <= DataIn;
                PWR_LOCY:       locy_h <= DataIn;
                PWR_BOTINFO:    botinfo_h <= DataIn;
                PWR_SENSORS:    sensors_h <= DataIn;
                PWR_LMDIST:     lmdist_h <= DataIn;
                PWR_RMDIST:     rmdist_h <= DataIn;
                PRW_LOADREGS:   load_sys_regs <= ~load_sys_regs;
                PRW_LDMOTDIST:  load_dist_regs <= ~load_dist_regs;
                PRW_UPDSYSREGS: upd_sysregs <= ~upd_sysregs;
                default: ;
            endcase
        end
    end

    // Visible registers: copied from the holding registers every clock while loading.
    always @(posedge clk) begin
        if (reset) begin
            {LocX, LocY, BotInfo, Sensors, LMDist, RMDist} <= 48'd0;
        end else begin
            if (load_sys_regs) {LocX, LocY, BotInfo, Sensors} <= {locx_h, locy_h, botinfo_h, sensors_h};
            if (load_dist_regs) {LMDist, RMDist} <= {lmdist_h, rmdist_h};
        end
    end

    // Reads need no strobe and only AddrIn[3:0] is decoded.
    wire unused_ok = &{1'b0, Rd_Strobe, AddrIn[7:4], 1'b0};
endmodule
