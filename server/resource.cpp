#include "resource.h"

namespace prt::serve {

BodySource memoryBody(std::string text) {
  BodySource body;
  body.size = text.size();
  body.memory = std::make_shared<const std::string>(std::move(text));
  return body;
}

}  // namespace prt::serve
