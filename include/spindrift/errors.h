// spindrift public API: the errors every call throws.
#pragma once

#include <spindrift/export.h>

#include <stdexcept>
#include <string>

namespace spindrift {

/// Thrown for invalid definitions, bad ids and I/O failures. The message says
/// what was wrong and what was expected.
class SPINDRIFT_API Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A field of a definition broke its rule. what() reads
/// "object: field: expected ..., got ..."; the parts are also available
/// separately. The field is named as a scene file spells its key path inside
/// the object ("iterations", "jet[0].speed", "shape.spread"), so the scene
/// loader can point at the line that set it.
class SPINDRIFT_API FieldError : public Error {
public:
    FieldError(std::string object, std::string field, std::string message);
    const std::string& object() const { return object_; }  ///< "fluid 'water'"
    const std::string& field() const { return field_; }
    const std::string& message() const { return message_; }  ///< the rule broken

private:
    std::string object_;
    std::string field_;
    std::string message_;
};

}  // namespace spindrift
