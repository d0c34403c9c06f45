#pragma once
// The GL 4.5 core entry points shaftlab uses, resolved at run time through the platform's
// GetProcAddress into one table (OSMesa's library does not export the direct-state-access
// functions, so nothing is linked directly). Call them as GL.CreateBuffers(...).
//
// One table per process: every backend (OSMesa, GLFW/GLX) returns context-independent pointers on
// Linux, and shaftlab never mixes backends in one process.

#include <GL/glcorearb.h>

namespace sl::gl {

// X(return-type-less PFN name, member name). Add an entry here to use a new entry point.
#define SL_GL_FUNCTIONS(X)                                                                         \
    X(PFNGLGETERRORPROC, GetError)                                                                 \
    X(PFNGLGETSTRINGPROC, GetString)                                                               \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                                                           \
    X(PFNGLENABLEPROC, Enable)                                                                     \
    X(PFNGLDISABLEPROC, Disable)                                                                   \
    X(PFNGLENABLEIPROC, Enablei)                                                                   \
    X(PFNGLDISABLEIPROC, Disablei)                                                                 \
    X(PFNGLVIEWPORTPROC, Viewport)                                                                 \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                                                               \
    X(PFNGLDEPTHMASKPROC, DepthMask)                                                               \
    X(PFNGLCULLFACEPROC, CullFace)                                                                 \
    X(PFNGLBLENDFUNCPROC, BlendFunc)                                                               \
    X(PFNGLBLENDFUNCIPROC, BlendFunci)                                                             \
    X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate)                                               \
    X(PFNGLBLENDEQUATIONPROC, BlendEquation)                                                       \
    X(PFNGLBLENDEQUATIONIPROC, BlendEquationi)                                                     \
    X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                                                       \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                                                           \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                                                             \
    X(PFNGLDRAWELEMENTSPROC, DrawElements)                                                         \
    X(PFNGLDEBUGMESSAGECALLBACKPROC, DebugMessageCallback)                                         \
    X(PFNGLDEBUGMESSAGECONTROLPROC, DebugMessageControl)                                           \
    X(PFNGLOBJECTLABELPROC, ObjectLabel)                                                           \
    X(PFNGLPUSHDEBUGGROUPPROC, PushDebugGroup)                                                     \
    X(PFNGLPOPDEBUGGROUPPROC, PopDebugGroup)                                                       \
    X(PFNGLCREATEBUFFERSPROC, CreateBuffers)                                                       \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                                       \
    X(PFNGLISBUFFERPROC, IsBuffer)                                                                 \
    X(PFNGLNAMEDBUFFERSTORAGEPROC, NamedBufferStorage)                                             \
    X(PFNGLNAMEDBUFFERSUBDATAPROC, NamedBufferSubData)                                             \
    X(PFNGLNAMEDBUFFERDATAPROC, NamedBufferData)                                                   \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                                                     \
    X(PFNGLCREATETEXTURESPROC, CreateTextures)                                                     \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                                     \
    X(PFNGLISTEXTUREPROC, IsTexture)                                                               \
    X(PFNGLTEXTURESTORAGE2DPROC, TextureStorage2D)                                                 \
    X(PFNGLTEXTURESTORAGE3DPROC, TextureStorage3D)                                                 \
    X(PFNGLTEXTURESUBIMAGE2DPROC, TextureSubImage2D)                                               \
    X(PFNGLTEXTURESUBIMAGE3DPROC, TextureSubImage3D)                                               \
    X(PFNGLTEXTUREPARAMETERIPROC, TextureParameteri)                                               \
    X(PFNGLBINDTEXTUREUNITPROC, BindTextureUnit)                                                   \
    X(PFNGLGETTEXTUREIMAGEPROC, GetTextureImage)                                                   \
    X(PFNGLCREATEFRAMEBUFFERSPROC, CreateFramebuffers)                                             \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                                             \
    X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, NamedFramebufferTexture)                                   \
    X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC, NamedFramebufferDrawBuffers)                           \
    X(PFNGLGETNAMEDFRAMEBUFFERATTACHMENTPARAMETERIVPROC, GetNamedFramebufferAttachmentParameteriv) \
    X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERPROC, NamedFramebufferDrawBuffer)                             \
    X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, CheckNamedFramebufferStatus)                           \
    X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, ClearNamedFramebufferfv)                                   \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                                                   \
    X(PFNGLCREATEVERTEXARRAYSPROC, CreateVertexArrays)                                             \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                                             \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                                                   \
    X(PFNGLVERTEXARRAYVERTEXBUFFERPROC, VertexArrayVertexBuffer)                                   \
    X(PFNGLVERTEXARRAYELEMENTBUFFERPROC, VertexArrayElementBuffer)                                 \
    X(PFNGLENABLEVERTEXARRAYATTRIBPROC, EnableVertexArrayAttrib)                                   \
    X(PFNGLVERTEXARRAYATTRIBFORMATPROC, VertexArrayAttribFormat)                                   \
    X(PFNGLVERTEXARRAYATTRIBBINDINGPROC, VertexArrayAttribBinding)                                 \
    X(PFNGLCREATESHADERPROC, CreateShader)                                                         \
    X(PFNGLDELETESHADERPROC, DeleteShader)                                                         \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                                                         \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                                                       \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                                                           \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                                                 \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                                       \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                                       \
    X(PFNGLATTACHSHADERPROC, AttachShader)                                                         \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                                                           \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                                         \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                                               \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                                                             \
    X(PFNGLPROGRAMUNIFORM1IPROC, ProgramUniform1i)                                                 \
    X(PFNGLPROGRAMUNIFORM2IPROC, ProgramUniform2i)                                                 \
    X(PFNGLPROGRAMUNIFORM4IPROC, ProgramUniform4i)                                                 \
    X(PFNGLPROGRAMUNIFORM1FPROC, ProgramUniform1f)                                                 \
    X(PFNGLPROGRAMUNIFORM3FVPROC, ProgramUniform3fv)                                               \
    X(PFNGLPROGRAMUNIFORM4FVPROC, ProgramUniform4fv)                                               \
    X(PFNGLPROGRAMUNIFORMMATRIX4FVPROC, ProgramUniformMatrix4fv)                                   \
    X(PFNGLGETUNIFORMBLOCKINDEXPROC, GetUniformBlockIndex)                                         \
    X(PFNGLGETACTIVEUNIFORMBLOCKIVPROC, GetActiveUniformBlockiv)                                   \
    X(PFNGLGETUNIFORMINDICESPROC, GetUniformIndices)                                               \
    X(PFNGLGETACTIVEUNIFORMSIVPROC, GetActiveUniformsiv)                                           \
    X(PFNGLCREATEQUERIESPROC, CreateQueries)                                                       \
    X(PFNGLGENQUERIESPROC, GenQueries)                                                             \
    X(PFNGLDELETEQUERIESPROC, DeleteQueries)                                                       \
    X(PFNGLBEGINQUERYPROC, BeginQuery)                                                             \
    X(PFNGLENDQUERYPROC, EndQuery)                                                                 \
    X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)                                           \
    X(PFNGLCREATESAMPLERSPROC, CreateSamplers)                                                     \
    X(PFNGLDELETESAMPLERSPROC, DeleteSamplers)                                                     \
    X(PFNGLSAMPLERPARAMETERIPROC, SamplerParameteri)                                               \
    X(PFNGLBINDSAMPLERPROC, BindSampler)                                                           \
    X(PFNGLGETTEXTURELEVELPARAMETERIVPROC, GetTextureLevelParameteriv)                             \
    X(PFNGLPROGRAMUNIFORM2FPROC, ProgramUniform2f)                                                 \
    X(PFNGLREADBUFFERPROC, ReadBuffer)                                                             \
    X(PFNGLREADPIXELSPROC, ReadPixels)                                                             \
    X(PFNGLCLEARNAMEDBUFFERDATAPROC, ClearNamedBufferData)                                         \
    X(PFNGLGETNAMEDBUFFERSUBDATAPROC, GetNamedBufferSubData)                                       \
    X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                                                       \
    X(PFNGLCOLORMASKPROC, ColorMask)                                                               \
    X(PFNGLSTENCILFUNCPROC, StencilFunc)                                                           \
    X(PFNGLSTENCILOPPROC, StencilOp)                                                               \
    X(PFNGLSTENCILMASKPROC, StencilMask)                                                           \
    X(PFNGLCLEARNAMEDFRAMEBUFFERFIPROC, ClearNamedFramebufferfi)                                   \
    X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                                                   \
    X(PFNGLDISPATCHCOMPUTEINDIRECTPROC, DispatchComputeIndirect)                                   \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                                                             \
    X(PFNGLBINDIMAGETEXTUREPROC, BindImageTexture)                                                 \
    X(PFNGLCLEARTEXIMAGEPROC, ClearTexImage)                                                       \
    X(PFNGLPOLYGONMODEPROC, PolygonMode)                                                           \
    X(PFNGLPROGRAMUNIFORM3FPROC, ProgramUniform3f)                                                 \
    X(PFNGLPROGRAMUNIFORM3IPROC, ProgramUniform3i)

struct Api {
#define SL_GL_DECLARE(type, name) type name = nullptr;
    SL_GL_FUNCTIONS(SL_GL_DECLARE)
#undef SL_GL_DECLARE
};

extern Api GL;

using ProcAddressFn = void* (*)(const char* name);
// Fills GL from `resolve`; throws sl::Error naming every entry point that did not resolve.
void load_api(ProcAddressFn resolve);

}  // namespace sl::gl
