// icon.v: a team's icon: each of the eight headings' two halves in its own ROM core
// (clean-room, written for botsim's tests); the cores' configurations were never committed.
`timescale 1ns / 1ps
module icon (
    input  wire [9:0] pixel_row,
    input  wire [9:0] pixel_column,
    input  wire [7:0] locx,
    input  wire [7:0] locy,
    input  wire [7:0] botinfo,
    output wire [1:0] icon
);
    wire [7:0] addr = {pixel_row[3:0], pixel_column[3:0]};
    wire [1:0] px [0:19];
    icon_rom_00 R00 (.a(addr), .spo(px[0]));
    icon_rom_01 R01 (.a(addr), .spo(px[1]));
    icon_rom_02 R02 (.a(addr), .spo(px[2]));
    icon_rom_03 R03 (.a(addr), .spo(px[3]));
    icon_rom_04 R04 (.a(addr), .spo(px[4]));
    icon_rom_05 R05 (.a(addr), .spo(px[5]));
    icon_rom_06 R06 (.a(addr), .spo(px[6]));
    icon_rom_07 R07 (.a(addr), .spo(px[7]));
    icon_rom_08 R08 (.a(addr), .spo(px[8]));
    icon_rom_09 R09 (.a(addr), .spo(px[9]));
    icon_rom_10 R10 (.a(addr), .spo(px[10]));
    icon_rom_11 R11 (.a(addr), .spo(px[11]));
    icon_rom_12 R12 (.a(addr), .spo(px[12]));
    icon_rom_13 R13 (.a(addr), .spo(px[13]));
    icon_rom_14 R14 (.a(addr), .spo(px[14]));
    icon_rom_15 R15 (.a(addr), .spo(px[15]));
    icon_rom_16 R16 (.a(addr), .spo(px[16]));
    icon_rom_17 R17 (.a(addr), .spo(px[17]));
    icon_rom_18 R18 (.a(addr), .spo(px[18]));
    icon_rom_19 R19 (.a(addr), .spo(px[19]));
    assign icon = px[{botinfo[2:0], pixel_row[4]} % 20];
    wire unused_ok = &{1'b0, locx, locy, pixel_row[9:5], pixel_column[9:4], 1'b0};
endmodule
