// The client colour buffer OSMesa needs to make a context current: memory Mesa may write into for
// as long as the process lives, so it is never freed.
//
// Why (Mesa's gallium OSMesa frontend, docs/stability.md): OSMesaMakeCurrent records the buffer
// it is given in an osmesa_buffer that Mesa keeps in a global list, found again by pixel format
// for the next context and not freed with the context (OSMesaDestroyContext frees the context
// only). Each flush of the front buffer (glFinish and glFlush on it, a make-current that unbinds)
// copies the frame into that pointer, until a later OSMesaMakeCurrent replaces it, which this
// program cannot observe. A block freed while Mesa still points to it is a write into freed
// memory: the one client buffer Mesa writes into, and the suspect of the intermittent segfault of
// issue 34 (a 32-bit zero written into a freed block of more than a kilobyte). occsim renders
// into its own framebuffer object, so what Mesa copies there is never read.
//
// Contexts of one size share one block (Mesa's list shares one osmesa_buffer per format anyway);
// a larger request gets a new block and the smaller ones stay allocated. Thread-safe.
#pragma once

#include <cstdint>

namespace occsim {

// A block of at least width * height * 4 bytes (RGBA8) that stays allocated until the process
// ends, after every static destructor (Mesa may flush from its own).
unsigned char* osmesaColourBuffer(uint32_t width, uint32_t height);

// True when `p` points into a block osmesaColourBuffer() handed out: a pointer Mesa was given
// stays valid (tests).
bool osmesaColourBufferIsKept(const void* p);

}  // namespace occsim
