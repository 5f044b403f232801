/* sdl_on_demand.c - the SDL 1.2 functions POV-Ray's display calls, loading SDL only when a
 * display is opened.
 *
 * Debian's libSDL-1.2 is sdl12-compat, which loads SDL2 and its hundred-odd libraries
 * (audio, X11, Wayland) from a constructor as soon as the process starts: about 6 ms of
 * CPU in every povray-fc process, most of a short process's start (`povray-fc --version`
 * took 10.0 ms of CPU with it, 4.1 ms without). Most renders never open a window (-D, a
 * render farm's slaves, fc-master's option probes), so this file is linked whole ahead of
 * POV-Ray's -lSDL, the linker (--as-needed) then leaves libSDL out of the binary, and the
 * first SDL_Init loads it. C, not C++: configure links its C test programs with the same
 * flags. Built with SDL's own header, so every signature is checked against the real one. */
#include <SDL.h>

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>

#define SDL_LIBRARY "libSDL-1.2.so.0"

/* One entry per function POV-Ray calls (nm -D --undefined-only on a build linked with the
 * real library); a test checks that the binary needs no libSDL, so a new call shows. */
#define SDL_FUNCTIONS(X)                                                                    \
    X(SDL_Init) X(SDL_GetError) X(SDL_CreateRGBSurface) X(SDL_DisplayFormat)                \
    X(SDL_FillRect) X(SDL_FreeSurface) X(SDL_GetRGBA) X(SDL_ListModes) X(SDL_LockSurface)   \
    X(SDL_MapRGBA) X(SDL_PollEvent) X(SDL_SetVideoMode) X(SDL_UnlockSurface)                \
    X(SDL_UpdateRect) X(SDL_UpperBlit)

static struct {
#define SDL_POINTER(name) __typeof__(&name) name;
    SDL_FUNCTIONS(SDL_POINTER)
#undef SDL_POINTER
} sdl;

static char load_error[512];
static pthread_once_t load_once = PTHREAD_ONCE_INIT;

/* dlsym on the library's handle finds its definitions, never the forwarders below. */
static void load_sdl(void)
{
    void *handle = dlopen(SDL_LIBRARY, RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char *why = dlerror();
        snprintf(load_error, sizeof load_error, "cannot load %s: %s", SDL_LIBRARY,
                 why ? why : "unknown error");
        return;
    }
#define SDL_RESOLVE(name) sdl.name = (__typeof__(&name))dlsym(handle, #name);
    SDL_FUNCTIONS(SDL_RESOLVE)
#undef SDL_RESOLVE
}

static void ensure_loaded(void)
{
    pthread_once(&load_once, load_sdl);
}

int SDLCALL SDL_Init(Uint32 flags)
{
    ensure_loaded();
    if (!sdl.SDL_Init) {
        if (!load_error[0])
            snprintf(load_error, sizeof load_error, "%s has no SDL_Init", SDL_LIBRARY);
        return -1;    /* POV-Ray prints SDL_GetError() and renders without a display */
    }
    return sdl.SDL_Init(flags);
}

char *SDLCALL SDL_GetError(void)
{
    ensure_loaded();
    return sdl.SDL_GetError ? sdl.SDL_GetError() : load_error;
}

/* The rest run only on a display whose SDL_Init succeeded, so the library is loaded; each
 * still passes through pthread_once, which is what makes the pointers set by SDL_Init's
 * thread visible to another (the console's main thread and vfe's worker both draw). */
SDL_Surface *SDLCALL SDL_CreateRGBSurface(Uint32 flags, int width, int height, int depth,
                                          Uint32 rmask, Uint32 gmask, Uint32 bmask, Uint32 amask)
{
    ensure_loaded();
    return sdl.SDL_CreateRGBSurface(flags, width, height, depth, rmask, gmask, bmask, amask);
}

SDL_Surface *SDLCALL SDL_DisplayFormat(SDL_Surface *surface)
{
    ensure_loaded();
    return sdl.SDL_DisplayFormat(surface);
}

int SDLCALL SDL_FillRect(SDL_Surface *dst, SDL_Rect *dstrect, Uint32 color)
{
    ensure_loaded();
    return sdl.SDL_FillRect(dst, dstrect, color);
}

void SDLCALL SDL_FreeSurface(SDL_Surface *surface)
{
    ensure_loaded();
    sdl.SDL_FreeSurface(surface);
}

void SDLCALL SDL_GetRGBA(Uint32 pixel, const SDL_PixelFormat *const fmt, Uint8 *r, Uint8 *g,
                         Uint8 *b, Uint8 *a)
{
    ensure_loaded();
    sdl.SDL_GetRGBA(pixel, fmt, r, g, b, a);
}

SDL_Rect **SDLCALL SDL_ListModes(SDL_PixelFormat *format, Uint32 flags)
{
    ensure_loaded();
    return sdl.SDL_ListModes(format, flags);
}

int SDLCALL SDL_LockSurface(SDL_Surface *surface)
{
    ensure_loaded();
    return sdl.SDL_LockSurface(surface);
}

Uint32 SDLCALL SDL_MapRGBA(const SDL_PixelFormat *const format, const Uint8 r, const Uint8 g,
                           const Uint8 b, const Uint8 a)
{
    ensure_loaded();
    return sdl.SDL_MapRGBA(format, r, g, b, a);
}

int SDLCALL SDL_PollEvent(SDL_Event *event)
{
    ensure_loaded();
    return sdl.SDL_PollEvent(event);
}

SDL_Surface *SDLCALL SDL_SetVideoMode(int width, int height, int bpp, Uint32 flags)
{
    ensure_loaded();
    return sdl.SDL_SetVideoMode(width, height, bpp, flags);
}

void SDLCALL SDL_UnlockSurface(SDL_Surface *surface)
{
    ensure_loaded();
    sdl.SDL_UnlockSurface(surface);
}

void SDLCALL SDL_UpdateRect(SDL_Surface *screen, Sint32 x, Sint32 y, Uint32 w, Uint32 h)
{
    ensure_loaded();
    sdl.SDL_UpdateRect(screen, x, y, w, h);
}

int SDLCALL SDL_UpperBlit(SDL_Surface *src, SDL_Rect *srcrect, SDL_Surface *dst,
                          SDL_Rect *dstrect)
{
    ensure_loaded();
    return sdl.SDL_UpperBlit(src, srcrect, dst, dstrect);
}
