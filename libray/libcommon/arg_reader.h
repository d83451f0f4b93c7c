// How primitives, textures and lights read their own arguments from a scene file.
//
// libshade implements this over its token stream; factories in libray read through it, so
// adding a primitive never touches the grammar. Every Read* call reports a located error
// (with the keyword's usage line) and throws FatalError when the next token does not fit,
// so factories need no error handling of their own for malformed input.
#pragma once

#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <utility>

#include "libcommon/data_file.h"
#include "libcommon/error.h"
#include "libcommon/vector.h"

namespace rs {

struct Surface;

// A number that may vary with time (animated transform or implicit skeleton parameters).
struct AnimatedValue {
    double value = 0;                  // the value when not animated
    std::function<double(double)> at;  // empty when static; else value at a time
    // When animated: an interval [lo, hi] holding at(t) for every t in [t0, t1], or
    // infinite ends where the reader cannot bound the value (see Expr::EvaluateRange).
    std::function<std::pair<double, double>(double, double)> range;
    // When animated and `affine`: at(t) == affineOffset + affineSlope * t bit for bit, for
    // every t (the reader checked the expression's form), which At computes without `at`.
    bool affine = false;
    double affineOffset = 0, affineSlope = 0;

    bool IsAnimated() const { return static_cast<bool>(at); }
    double At(double time) const {
        if (affine) return affineOffset + affineSlope * time;
        return at ? at(time) : value;
    }
};

class ArgReader {
  public:
    virtual ~ArgReader() = default;

    // Static numbers: NUMBER, ±NUMBER or a parenthesised expression (spec §1.4).
    virtual double ReadNumber() = 0;
    // As ReadNumber, truncated toward zero.
    virtual int ReadInt() = 0;
    Vec3 ReadVector() {
        double x = ReadNumber(), y = ReadNumber(), z = ReadNumber();
        return {x, y, z};
    }
    Color ReadColor() {
        double r = ReadNumber(), g = ReadNumber(), b = ReadNumber();
        return {r, g, b};
    }
    // A number that may depend on time, frame or linear().
    virtual AnimatedValue ReadAnimatedNumber() = 0;

    // True when the next token can start a number (so open-ended lists can loop).
    virtual bool PeekNumber() = 0;
    // Consumes the next token if it is the keyword, name or punctuation character `word`;
    // returns whether it did.
    virtual bool Accept(const char* word) = 0;
    // True when the next token is the keyword or name `word` (nothing consumed).
    virtual bool Peek(const char* word) = 0;
    // A NAME token.
    virtual std::string ReadName() = 0;
    // A NAME token or a keyword of the scene language, as written (for sub-languages whose
    // names are their own, such as an implicit block's skeleton names). By default ReadName.
    virtual std::string ReadWord() { return ReadName(); }
    // True when the next token is a name or a keyword (nothing consumed).
    virtual bool PeekWord() { return !PeekNumber(); }
    // A file name as written (relative names are relative to the working directory).
    virtual std::string ReadFilename() = 0;
    // The name of a file the scene reads (height field, image, colormap): as ReadFilename,
    // then resolved by ResolveDataFile against the file holding the current keyword.
    std::string ReadDataFilename() {
        const SourceLocation where = Location();
        return ResolveDataFile(ReadFilename(), where.file);
    }
    // True when the next token can start a file name (optional file arguments).
    virtual bool PeekFilename() = 0;
    // A surface expression (spec §2 `surface`): attributes, a surface name, or cursurf.
    virtual Surface ReadSurface() = 0;

    // The -f flag: triangles and polygons flip their normals when it is set.
    virtual bool FlipNormals() const = 0;

    // Where the current keyword started, for messages.
    virtual SourceLocation Location() const = 0;
    // A warning at the current location (primitives use it for degenerate input before
    // returning nullptr, which discards the object as the original does).
    virtual void Warn(const std::string& message) = 0;
    virtual void Advise(const std::string& message) = 0;
    // A fatal error at the current location, with the keyword's usage line appended.
    [[noreturn]] virtual void Fail(const std::string& message) = 0;

    // Where the next token starts, so a block spanning lines can place each statement; the
    // keyword's location by default.
    virtual SourceLocation NextLocation() { return Location(); }
    // Warn and Fail at a location of this argument list (from NextLocation).
    virtual void WarnAtLocation(const SourceLocation& where, const std::string& message) {
        static_cast<void>(where);
        Warn(message);
    }
    [[noreturn]] virtual void FailAtLocation(const SourceLocation& where,
                                             const std::string& message) {
        static_cast<void>(where);
        Fail(message);
        std::abort();  // not reached (Fail throws); gcc does not see through the virtual call
    }
};

}  // namespace rs
