# frozen_string_literal: true

# Admonition convention: a blockquote whose first words are a bold "Tip", "Note" or
# "Warning" becomes a box of that kind.
#
#     > **Warning:** catkin_make deletes build/ and devel/ it did not make.
#
# kramdown renders it as `<blockquote><p><strong>Warning:</strong> ...`; this hook turns
# the blockquote into `<aside class="admonition admonition-warning" role="note">`, so that
# the label stays in the text (for screen readers, and in the notebooks, where the same
# Markdown is a plain quote) and the box only adds colour and space.
module Sw2simSite
  module Admonitions
    KINDS = %w[Tip Note Warning].freeze
    BOX = %r{<blockquote>(\s*<p><strong>(#{KINDS.join("|")})[.:]?</strong>.*?)</blockquote>}m.freeze

    module_function

    def wrap(html)
      html.gsub(BOX) do
        body, kind = Regexp.last_match(1), Regexp.last_match(2)
        %(<aside class="admonition admonition-#{kind.downcase}" role="note">#{body}</aside>)
      end
    end
  end
end

Jekyll::Hooks.register [:pages, :documents], :post_convert do |page|
  next unless page.output_ext == ".html"

  page.content = Sw2simSite::Admonitions.wrap(page.content)
end
