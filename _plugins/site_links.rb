# frozen_string_literal: true

# Lets page authors write site links and image paths from the site root,
#
#     [the exported package](/practice-1/exported-package/)
#     ![The wheel](/media/practice-1/wheel.png)
#
# and still have them work when the site is published under a sub-path (GitHub Pages
# project sites: the Pages workflow builds with --baseurl "/<repository>"). Root-relative
# href and src attributes of the page body get the baseurl in front, unless they already
# start with it (written with `| relative_url`). Protocol-relative `//host/...` links and
# code blocks (their text is escaped, so never matches) are untouched.
module Sw2simSite
  module SiteLinks
    ROOT_RELATIVE = %r{\b(href|src)="(/(?!/)[^"]*)"}.freeze

    module_function

    def prefix(html, baseurl)
      base = baseurl.to_s.chomp("/")
      return html if base.empty?

      html.gsub(ROOT_RELATIVE) do
        attribute = Regexp.last_match(1)
        path = Regexp.last_match(2)
        already = path == base || path.start_with?("#{base}/")
        %(#{attribute}="#{already ? path : base + path}")
      end
    end
  end
end

Jekyll::Hooks.register [:pages, :documents], :post_convert do |page|
  next unless page.output_ext == ".html"

  page.content = Sw2simSite::SiteLinks.prefix(page.content, page.site.baseurl)
end
