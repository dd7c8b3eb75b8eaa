/* board_abi.h: the C interface of a board simulation library (harness.cpp). */
#include <stddef.h>
#include <stdint.h>

typedef struct Board Board;

enum { BOARD_EVENT_DISPLAY = 1, BOARD_EVENT_LEDS = 2, BOARD_EVENT_SAMPLE = 3, BOARD_EVENT_VGA = 4 };
enum { BOARD_UNTIL = 0, BOARD_BUFFER_FULL = 1, BOARD_SAMPLES = 2, BOARD_FINISHED = 3 };

/* One thing the board showed. DISPLAY: a = an | seg << 8 | dp << 15. LEDS: a = led.
 * SAMPLE: a = sample index, b = LocX | LocY << 8 | BotInfo << 16 | Sensors << 24 |
 * LMDist << 32 | RMDist << 40 | MotCtl << 48, c = the bot's clock cycles since power-up.
 * VGA (when board_record_vga is on): a = r << 8 | g << 4 | b | hsync << 12 | vsync << 13. */
typedef struct BoardEvent {
    uint64_t time_ps;
    uint32_t kind;
    uint32_t a;
    uint64_t b;
    uint64_t c;
} BoardEvent;
