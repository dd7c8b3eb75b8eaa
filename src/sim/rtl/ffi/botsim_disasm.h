// botsim_disasm.h: the text of a KCPSM6 instruction word for the debug signal kcpsm6_opcode
// (rtl/kcpsm6.v's DPI import `botsim_disasm`, in BOTSIM_DEBUG builds), shared by the bot
// model's shim and the board harness. The disassembler is Rust's (kcpsm6::disasm), reached
// through `fill`; the 20 characters are packed into the signal's bits [1:160], first
// character in the top byte. A word's text never changes, and a program shows few words at a
// time (a loop's): the last ones are kept.
#pragma once

#include <cstdint>

#include "svdpi.h"

template <class Fill>
inline void botsim_disasm_pack(int word, svBitVecVal* text, Fill fill) {
    struct Entry {
        int word = -1;
        svBitVecVal text[5];
    };
    static thread_local Entry cache[256];
    Entry& e = cache[(word ^ word >> 8 ^ word >> 16) & 255];
    if (e.word != word) {
        char s[20];
        for (char& c : s) c = ' ';
        if (!fill((uint32_t)word, s)) {
            for (int w = 0; w < 5; w++) text[w] = 0x20202020;
            return;
        }
        for (int w = 0; w < 5; w++) e.text[w] = 0;
        for (int i = 0; i < 20; i++) e.text[(159 - 8 * i) / 32] |= (uint32_t)(uint8_t)s[i] << ((152 - 8 * i) % 32);
        e.word = word;
    }
    for (int w = 0; w < 5; w++) text[w] = e.text[w];
}
