// dtg.v: botsim's stand-in for the course's display timing generator `dtg`, for designs
// whose repository does not carry it (clean-room, from spec board.md §1; written for botsim):
// 640 x 480 at 60 Hz on a 25 MHz pixel clock, 800 clocks per line (640 visible, 16 front
// porch, 96 sync, 48 back porch), 525 lines per frame (480, 10, 2, 33), syncs active low.
// As in the course's display (and botsim's own frames), video_on covers the 512 columns the
// 128-cell world fills. The row and column are wide enough for any connection.
`timescale 1ns / 1ps
module dtg (
    input  wire        clock,
    input  wire        rst,
    output reg         horiz_sync = 1'b1,
    output reg         vert_sync = 1'b1,
    output reg         video_on = 1'b0,
    output reg  [10:0] pixel_row = 11'd0,
    output reg  [10:0] pixel_column = 11'd0
);
    localparam [10:0] H_VISIBLE = 640, H_SYNC_START = 656, H_SYNC_END = 752, H_TOTAL = 800;
    localparam [10:0] V_VISIBLE = 480, V_SYNC_START = 490, V_SYNC_END = 492, V_TOTAL = 525;
    localparam [10:0] ACTIVE_WIDTH = 512;

    wire [10:0] next_col = (pixel_column == H_TOTAL - 1) ? 11'd0 : pixel_column + 11'd1;
    wire [10:0] next_row = (pixel_column != H_TOTAL - 1) ? pixel_row
                         : (pixel_row == V_TOTAL - 1) ? 11'd0 : pixel_row + 11'd1;

    always @(posedge clock) begin
        if (rst) begin
            pixel_column <= 11'd0;
            pixel_row <= 11'd0;
            horiz_sync <= 1'b1;
            vert_sync <= 1'b1;
            video_on <= 1'b0;
        end else begin
            pixel_column <= next_col;
            pixel_row <= next_row;
            horiz_sync <= !(next_col >= H_SYNC_START && next_col < H_SYNC_END);
            vert_sync <= !(next_row >= V_SYNC_START && next_row < V_SYNC_END);
            video_on <= next_col < ACTIVE_WIDTH && next_row < V_VISIBLE;
        end
    end
    wire unused_ok = &{1'b0, H_VISIBLE[0], 1'b0};
endmodule
