// gl_context.cpp: EGL through dlopen (no link-time libEGL), a configless surfaceless OpenGL 4.5 core context,
// and the GL entry points of gl_api.hpp through eglGetProcAddress (Mesa exports core functions there too:
// EGL_KHR_client_get_all_proc_addresses).
#include "gl/gl_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace idk::gl {

// libEGL stays loaded for the process once opened: unloading a GL driver while its atexit handlers are
// registered crashes at exit, so the handle is never dlclose'd.
struct EglLibrary {
    decltype(&eglGetProcAddress) getProcAddress = nullptr;
    decltype(&eglQueryString) queryString = nullptr;
    decltype(&eglInitialize) initialize = nullptr;
    decltype(&eglTerminate) terminate = nullptr;
    decltype(&eglBindAPI) bindApi = nullptr;
    decltype(&eglCreateContext) createContext = nullptr;
    decltype(&eglDestroyContext) destroyContext = nullptr;
    decltype(&eglMakeCurrent) makeCurrent = nullptr;
    decltype(&eglGetError) getError = nullptr;
    decltype(&eglReleaseThread) releaseThread = nullptr;
    PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay = nullptr;
    PFNEGLQUERYDEVICESEXTPROC queryDevices = nullptr;
};

namespace {

std::shared_ptr<EglLibrary> loadEgl(std::string* whyNot) {
    void* handle = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        *whyNot = "libEGL.so.1 not found (Debian packages libegl1 and libegl-mesa0)";
        return nullptr;
    }
    auto egl = std::make_shared<EglLibrary>();
    bool ok = true;
    auto sym = [&](auto& fn, const char* name) {
        fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(dlsym(handle, name));
        ok = ok && fn != nullptr;
    };
    sym(egl->getProcAddress, "eglGetProcAddress");
    sym(egl->queryString, "eglQueryString");
    sym(egl->initialize, "eglInitialize");
    sym(egl->terminate, "eglTerminate");
    sym(egl->bindApi, "eglBindAPI");
    sym(egl->createContext, "eglCreateContext");
    sym(egl->destroyContext, "eglDestroyContext");
    sym(egl->makeCurrent, "eglMakeCurrent");
    sym(egl->getError, "eglGetError");
    sym(egl->releaseThread, "eglReleaseThread");
    if (!ok) {
        *whyNot = "libEGL.so.1 lacks EGL 1.5 entry points";
        return nullptr;
    }
    egl->getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(egl->getProcAddress("eglGetPlatformDisplayEXT"));
    egl->queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(egl->getProcAddress("eglQueryDevicesEXT"));
    return egl;
}

bool hasWord(const char* list, const char* word) {
    if (!list) return false;
    const size_t n = std::strlen(word);
    for (const char* p = std::strstr(list, word); p; p = std::strstr(p + 1, word))
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

std::string hex(int value) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%04x", value);
    return text;
}

}  // namespace

std::unique_ptr<GlContext> GlContext::create(std::string* whyNot) {
    std::string reason;
    if (const char* env = std::getenv("IDK_GL_INTEROP"); env && std::string(env) == "off") {
        reason = "disabled by IDK_GL_INTEROP=off (EGL not loaded)";
    } else {
        std::unique_ptr<GlContext> ctx(new GlContext());
        if (ctx->init(&reason)) return ctx;
    }
    if (whyNot) *whyNot = reason;
    return nullptr;
}

bool GlContext::init(std::string* whyNot) {
    egl_ = loadEgl(whyNot);
    if (!egl_) return false;
    const char* client = egl_->queryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!egl_->getPlatformDisplay) {
        *whyNot = "EGL lacks eglGetPlatformDisplayEXT (EGL_EXT_platform_base)";
        return false;
    }
    std::string tried;
    // Surfaceless first: Mesa's platform without a window system, which picks the default renderer.
    if (hasWord(client, "EGL_MESA_platform_surfaceless")) {
        void* display = egl_->getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display && tryDisplay(display, "surfaceless", &tried)) return true;
    }
    // Then every EGL device (EGL_EXT_platform_device: one per GPU, plus the software renderer).
    if (hasWord(client, "EGL_EXT_platform_device") && egl_->queryDevices) {
        EGLDeviceEXT devices[16];
        EGLint count = 0;
        if (egl_->queryDevices(16, devices, &count)) {
            for (EGLint i = 0; i < count; ++i) {
                void* display = egl_->getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
                if (display && tryDisplay(display, "device " + std::to_string(i), &tried)) return true;
            }
        }
    }
    *whyNot = tried.empty() ? "EGL has neither the surfaceless nor the device platform" : tried;
    return false;
}

bool GlContext::tryDisplay(void* display, const std::string& platform, std::string* whyNot) {
    auto fail = [&](const std::string& why) {
        *whyNot += (whyNot->empty() ? "" : "; ") + platform + ": " + why;
        return false;
    };
    EGLint major = 0, minor = 0;
    if (!egl_->initialize(display, &major, &minor)) return fail("eglInitialize failed (" + hex(egl_->getError()) + ")");
    auto abandon = [&](const std::string& why) {
        egl_->terminate(display);
        return fail(why);
    };
    if (!hasWord(egl_->queryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
        return abandon("no EGL_KHR_surfaceless_context");
    if (!egl_->bindApi(EGL_OPENGL_API)) return abandon("eglBindAPI(EGL_OPENGL_API) failed");
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    void* context = egl_->createContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (!context) return abandon("no OpenGL 4.5 core context (" + hex(egl_->getError()) + ")");
    display_ = display;
    context_ = context;
    platform_ = platform;
    if (!egl_->makeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        egl_->destroyContext(display, context);
        context_ = nullptr;
        return abandon("eglMakeCurrent failed (" + hex(egl_->getError()) + ")");
    }
    std::string missing;
#define IDK_GL_LOAD(name, type)                                                        \
    api_.name = reinterpret_cast<type>(egl_->getProcAddress(#name));                   \
    if (!api_.name) missing += (missing.empty() ? "" : ", ") + std::string(#name);
    IDK_GL_FUNCTIONS(IDK_GL_LOAD)
#undef IDK_GL_LOAD
    // Optional: Mesa returns dispatch stubs for names it knows even where the driver lacks the extension, so the
    // extension string decides (in gl_sync.cpp), not these pointers alone.
#define IDK_GL_LOAD_OPTIONAL(name, type) api_.name = reinterpret_cast<type>(egl_->getProcAddress(#name));
    IDK_GL_SEMAPHORE_FUNCTIONS(IDK_GL_LOAD_OPTIONAL)
#undef IDK_GL_LOAD_OPTIONAL
    if (missing.empty()) {
        version_ = reinterpret_cast<const char*>(api_.glGetString(GL_VERSION));
        renderer_ = reinterpret_cast<const char*>(api_.glGetString(GL_RENDERER));
        GLint count = 0;
        api_.glGetIntegerv(GL_NUM_EXTENSIONS, &count);
        for (GLint i = 0; i < count; ++i)
            extensions_.emplace_back(reinterpret_cast<const char*>(api_.glGetStringi(GL_EXTENSIONS, GLuint(i))));
        if (hasExtension("GL_EXT_memory_object")) {
            deviceUuid_.assign(GL_UUID_SIZE_EXT, 0);
            driverUuid_.assign(GL_UUID_SIZE_EXT, 0);
            api_.glGetUnsignedBytevEXT(GL_DRIVER_UUID_EXT, driverUuid_.data());
            // GL_DEVICE_UUID_EXT is indexed (one per device of the context); index 0 is the device of the context.
            auto getUuid = reinterpret_cast<PFNGLGETUNSIGNEDBYTEI_VEXTPROC>(egl_->getProcAddress("glGetUnsignedBytei_vEXT"));
            if (getUuid) getUuid(GL_DEVICE_UUID_EXT, 0, deviceUuid_.data());
        }
        api_.glGetError();  // an unsupported query above must not surface in the first check()
    }
    egl_->makeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (!missing.empty()) {
        egl_->destroyContext(display, context);
        context_ = nullptr;
        return abandon("the GL driver lacks " + missing);
    }
    return true;
}

GlContext::~GlContext() {
    if (!egl_ || !display_) return;
    egl_->makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_) egl_->destroyContext(display_, context_);
    egl_->terminate(display_);
    egl_->releaseThread();
}

GlContext::Current::Current(const GlContext& ctx) : ctx_(ctx), lock_(ctx.mutex_) {
    if (!ctx_.egl_->makeCurrent(ctx_.display_, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx_.context_))
        throw GlError("eglMakeCurrent failed (" + hex(ctx_.egl_->getError()) + ")");
}

GlContext::Current::~Current() {
    ctx_.egl_->makeCurrent(ctx_.display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

bool GlContext::hasExtension(const std::string& name) const {
    return std::find(extensions_.begin(), extensions_.end(), name) != extensions_.end();
}

void GlContext::check(const std::string& what) const {
    const GLenum error = api_.glGetError();
    if (error != GL_NO_ERROR) throw GlError("OpenGL: " + what + " failed (GL error " + hex(int(error)) + ")");
}

}  // namespace idk::gl
