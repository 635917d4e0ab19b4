# frozen_string_literal: true

# Adds loading="lazy" to every <img> of a rendered page that does not say how to load,
# so long pages fetch figures as the reader scrolls to them. It has to be in the HTML
# itself: a script setting it after parsing comes too late, the fetch has started.
# An image written with its own `loading` attribute (e.g. loading="eager") is left alone.
module Sw2simSite
  module LazyImages
    IMG_WITHOUT_LOADING = /<img\b(?![^>]*\bloading=)/i.freeze

    module_function

    def mark(html)
      html.gsub(IMG_WITHOUT_LOADING, '<img loading="lazy"')
    end
  end
end

Jekyll::Hooks.register [:pages, :documents], :post_render do |page|
  next unless page.output_ext == ".html"

  page.output = Sw2simSite::LazyImages.mark(page.output)
end
