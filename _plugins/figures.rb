# frozen_string_literal: true

# Figure convention: an image followed, on the next line of the same paragraph, by an
# italic line becomes a <figure> whose caption is that line.
#
#     ![The wheel, its bracket and the axle](/media/practice-1/wheel.png)
#     *The wheel part in its bracket.*
#
# kramdown renders that paragraph as `<p><img ... />\n<em>caption</em></p>`; this hook
# rewrites it after conversion. An image alone in its paragraph stays as it is. Write
# the alt text for readers who cannot see the image; the caption is for everyone.
module Sw2simSite
  module Figures
    CAPTIONED_IMAGE = %r{<p>\s*(<img\b[^>]*>)\s*<em>(.*?)</em>\s*</p>}m.freeze

    module_function

    def wrap(html)
      html.gsub(CAPTIONED_IMAGE) do
        %(<figure class="figure">#{Regexp.last_match(1)}<figcaption>#{Regexp.last_match(2)}</figcaption></figure>)
      end
    end
  end
end

Jekyll::Hooks.register [:pages, :documents], :post_convert do |page|
  next unless page.output_ext == ".html"

  page.content = Sw2simSite::Figures.wrap(page.content)
end
